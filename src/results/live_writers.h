#pragma once
/// The ResultsWriters open in this process, by file: a ResultsReader that opens a file a writer
/// of the same process is writing makes it sync first (its buffered points reach the file), so
/// POST1, POST26 and *GET after a SOLVE see every point appended so far. Readers in other
/// processes see the points up to the writer's last sync (docs/results_file.md).
#include <string>

namespace impactfe {

/// Syncs the writer of `path` when one is open in this process; nothing otherwise.
void sync_live_writer(const std::string& path);

}  // namespace impactfe
