#pragma once
/// Figures added to an analysis of a results file after the analysis was written: under MPI a
/// superelement generated on another rank (docs/scaling.md, "Substructures in parallel") has
/// its summary only once the owner's file arrives, when rank 0's results group is long written.
#include <map>
#include <string>

namespace impactfe {

/// Sets attributes of /analysis_<analysis> (1-based) of the results file at `path`, as
/// ResultsWriter::set_count (`counts`) and set_attribute (`values`) write them. The file may
/// still be open in a ResultsWriter of this process (HDF5 then shares the open file). Only when
/// the analysis still is the one meant, i.e. its text attribute `key` equals `key_value` (a
/// later job of the same name may have replaced the file): returns whether it was.
bool amend_analysis_attributes(const std::string& path, int analysis, const std::string& key,
                               const std::string& key_value,
                               const std::map<std::string, long long>& counts,
                               const std::map<std::string, double>& values);

}  // namespace impactfe
