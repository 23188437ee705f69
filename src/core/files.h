#pragma once
/// File-name lookups that never throw: file names come from decks. The deck-level reads (the
/// deck, /INPUT and macro files, *LIST, RESUME, superelement look-ups) go through file_exists
/// and read_file, which a distributed run (docs/scaling.md) points at rank 0's disk.
#include <optional>
#include <string>

namespace impactfe {

/// Whether `path` names a regular file (`exists_only`: anything), false when the name cannot be
/// looked up at all (longer than the system allows, a component that is not a directory):
/// std::filesystem's throwing overloads would escape as a library message without FILE:LINE
/// (a fuzzing finding, issue 12: `*AAAA...` with a 300-character name looked for AAAA....mac).
bool file_exists(const std::string& path, bool exists_only = false);

/// The bytes of the file `path`; nullopt when it cannot be opened or is a directory.
std::optional<std::string> read_file(const std::string& path);

/// The same on this process's own disk, whatever the hooks.
bool local_file_exists(const std::string& path, bool exists_only = false);
std::optional<std::string> local_read_file(const std::string& path);

/// Replaces the two lookups above (nullptr: this process's disk again). Set once at start-up by
/// the distributed run (linalg/parallel_backend.h, share_rank0_files), before any deck is read.
using FileExistsHook = bool (*)(const std::string& path, bool exists_only);
using ReadFileHook = std::optional<std::string> (*)(const std::string& path);
void set_file_hooks(FileExistsHook exists, ReadFileHook read);

}  // namespace impactfe
