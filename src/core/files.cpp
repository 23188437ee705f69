#include "core/files.h"

#include <filesystem>
#include <fstream>
#include <sstream>
#include <system_error>

namespace impactfe {

namespace {
FileExistsHook exists_hook = nullptr;
ReadFileHook read_hook = nullptr;
}  // namespace

bool local_file_exists(const std::string& path, bool exists_only) {
  std::error_code ec;
  return exists_only ? std::filesystem::exists(path, ec)
                     : std::filesystem::is_regular_file(path, ec);
}

std::optional<std::string> local_read_file(const std::string& path) {
  std::error_code ec;
  if (std::filesystem::is_directory(path, ec)) return std::nullopt;
  std::ifstream in(path, std::ios::binary);
  if (!in) return std::nullopt;
  std::ostringstream ss;
  ss << in.rdbuf();
  return ss.str();
}

bool file_exists(const std::string& path, bool exists_only) {
  return exists_hook ? exists_hook(path, exists_only) : local_file_exists(path, exists_only);
}

std::optional<std::string> read_file(const std::string& path) {
  return read_hook ? read_hook(path) : local_read_file(path);
}

void set_file_hooks(FileExistsHook exists, ReadFileHook read) {
  exists_hook = exists;
  read_hook = read;
}

}  // namespace impactfe
