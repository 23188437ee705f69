#include "results/results_amend.h"

#include <fmt/format.h>
#include <hdf5.h>

#include "core/errors.h"
#include "io/h5_util.h"
#include "results/live_writers.h"

namespace impactfe {

bool amend_analysis_attributes(const std::string& path, int analysis, const std::string& key,
                               const std::string& key_value,
                               const std::map<std::string, long long>& counts,
                               const std::map<std::string, double>& values) {
  h5::silence_errors();
  // A writer of this process first writes what it was given (its analysis group included).
  sync_live_writer(path);
  // The access list of ResultsWriter: HDF5 opens a file a second time only with the same one.
  h5::Handle fapl = h5::file_access_checksummed();
  const hid_t f = H5Fopen(path.c_str(), H5F_ACC_RDWR, fapl);
  if (f < 0)
    throw SolutionError(
        fmt::format("cannot open results file '{}' to add figures to analysis {}", path, analysis));
  h5::Handle file(f);
  const std::string name = fmt::format("analysis_{}", analysis);
  if (!h5::exists(file, name)) return false;
  h5::Handle group = h5::open_group(file, name);
  if (H5Aexists(group, key.c_str()) <= 0 || h5::read_string_attribute(group, key) != key_value)
    return false;
  for (const auto& [name, value] : counts) h5::write_integer_attribute(group, name, value);
  for (const auto& [name, value] : values) h5::write_attribute(group, name, value);
  H5Fflush(file, H5F_SCOPE_LOCAL);
  return true;
}

}  // namespace impactfe
