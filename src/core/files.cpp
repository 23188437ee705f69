#include "core/files.h"

#include <fmt/format.h>

#include <algorithm>
#include <cstdint>
#include <cstring>
#include <filesystem>
#include <fstream>
#include <sstream>
#include <system_error>
#include <vector>

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

OversizedFileError::OversizedFileError(const std::string& path, int line, std::size_t limit)
    : std::runtime_error(
          line > 0 ? fmt::format("{}:{}: a line longer than {} bytes: refused (is it a text file?)",
                                 path, line, limit)
                   : fmt::format("{}: larger than {} bytes: refused", path, limit)),
      line_(line),
      limit_(limit) {}

std::optional<std::string> local_read_file(const std::string& path, const ReadLimits& limits) {
  std::error_code ec;
  if (std::filesystem::is_directory(path, ec)) return std::nullopt;
  std::ifstream in(path, std::ios::binary);
  if (!in) return std::nullopt;
  // Read in pieces, so that a device or a pipe without end (/dev/zero) stops at a bound.
  std::string text;
  // A regular file's size is known: one allocation instead of doubling copies (a 10⁶-node CDB
  // archive is ~300 MB).
  const auto size = std::filesystem::file_size(path, ec);
  if (!ec && std::filesystem::is_regular_file(path, ec))
    text.reserve(static_cast<std::size_t>(std::min<std::uintmax_t>(size, limits.max_bytes)));
  std::vector<char> piece(std::size_t{1} << 16);
  int line = 1;
  std::size_t line_start = 0;  // offset in `text` of the current line
  while (in) {
    in.read(piece.data(), static_cast<std::streamsize>(piece.size()));
    const auto got = static_cast<std::size_t>(in.gcount());
    if (got == 0) break;
    if (text.size() + got > limits.max_bytes) throw OversizedFileError(path, 0, limits.max_bytes);
    const std::size_t old_size = text.size();
    text.append(piece.data(), got);
    if (limits.max_line == 0) continue;
    for (const char* at = text.data() + old_size;
         (at = static_cast<const char*>(
              std::memchr(at, '\n', static_cast<std::size_t>(text.data() + text.size() - at))));
         ++at) {
      const auto end = static_cast<std::size_t>(at - text.data());
      if (end - line_start > limits.max_line) throw OversizedFileError(path, line, limits.max_line);
      ++line;
      line_start = end + 1;
    }
    if (text.size() - line_start > limits.max_line)
      throw OversizedFileError(path, line, limits.max_line);
  }
  return text;
}

std::string jobname_problem(const std::string& name, const std::string& what) {
  if (name.empty()) return "the " + what + " is empty";
  if (name == "." || name == "..") return what + " '" + name + "' names a directory, not a file";
  if (name.find_first_of(std::string("/\\\0", 3)) != std::string::npos)
    return what + " '" + name + "' contains a path separator: a " + what +
           " names files in the output directory (choose the directory with -o)";
  return {};
}

bool file_exists(const std::string& path, bool exists_only) {
  return exists_hook ? exists_hook(path, exists_only) : local_file_exists(path, exists_only);
}

std::optional<std::string> read_file(const std::string& path, const ReadLimits& limits) {
  return read_hook ? read_hook(path, limits) : local_read_file(path, limits);
}

void set_file_hooks(FileExistsHook exists, ReadFileHook read) {
  exists_hook = exists;
  read_hook = read;
}

}  // namespace impactfe
