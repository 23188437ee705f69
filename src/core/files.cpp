#include "core/files.h"

#include <filesystem>
#include <system_error>

namespace impactfe {

bool file_exists(const std::string& path, bool exists_only) {
  std::error_code ec;
  return exists_only ? std::filesystem::exists(path, ec)
                     : std::filesystem::is_regular_file(path, ec);
}

}  // namespace impactfe
