#pragma once
/// The ResultsWriters open in this process, by file: a ResultsReader that opens a file a writer
/// of the same process is writing makes it sync first (its buffered points reach the file), so
/// POST1, POST26 and *GET after a SOLVE see every point appended so far. Readers in other
/// processes see the points up to the writer's last sync (docs/results_file.md).
#include <functional>
#include <string>

namespace impactfe {

/// Syncs the writer of `path` when one is open in this process; nothing otherwise.
void sync_live_writer(const std::string& path);

/// A writer registers its file with its sync and removes it when it closes (`owner`: the
/// writer, so that a later writer of the same file is not removed by an earlier one).
void register_live_writer(const std::string& path, const void* owner, std::function<void()> sync);
void unregister_live_writer(const std::string& path, const void* owner);

}  // namespace impactfe
