#pragma once
/// File-name lookups that never throw: file names come from decks.
#include <string>

namespace impactfe {

/// Whether `path` names a regular file (`exists_only`: anything), false when the name cannot be
/// looked up at all (longer than the system allows, a component that is not a directory):
/// std::filesystem's throwing overloads would escape as a library message without FILE:LINE
/// (a fuzzing finding, issue 12: `*AAAA...` with a 300-character name looked for AAAA....mac).
bool file_exists(const std::string& path, bool exists_only = false);

}  // namespace impactfe
