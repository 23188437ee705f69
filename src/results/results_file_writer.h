#pragma once
/// The writer of a results file itself: every HDF5 call of writing <jobname>.h5, made on the
/// thread that calls it. ResultsWriter (results_file.h) is what the analyses use: it runs this
/// on a thread of its own when the run has two (issue 11). Schema: docs/results_file.md.
#include <map>
#include <memory>
#include <string>
#include <vector>

#include "results/results_file.h"

namespace impactfe {

/// The model section of a results file (/model), taken from the Model on the caller's thread:
/// the writer may write it on another, after the Model has changed or gone.
struct ResultsModelSection {
  std::string title, jobname;
  std::string units;             // /UNITS label; empty: not given (no attribute written)
  std::vector<int> node_ids;     // ascending
  std::vector<double> node_xyz;  // x y z per node
  std::vector<int> element_ids;  // ascending
  std::vector<std::string> element_type_names;  // ANSYS names ("" for an undefined type)
  std::vector<int> element_types, element_materials, element_reals;
  std::vector<std::vector<int>> element_nodes;

  static ResultsModelSection of(const Model& model);
};

/// Writes <jobname>.h5 on the calling thread; the operations of ResultsWriter (results_file.h),
/// with the same contracts.
class ResultsFileWriter {
 public:
  ResultsFileWriter(const std::string& path, const ResultsModelSection& model);
  ResultsFileWriter(const std::string& path, ResultsWriter::Append);
  ~ResultsFileWriter();
  ResultsFileWriter(const ResultsFileWriter&) = delete;
  ResultsFileWriter& operator=(const ResultsFileWriter&) = delete;

  int begin_analysis(ResultsKind kind, const std::string& description,
                     long long expected_points = 0);
  void append(const TimePoint& point);
  void set_sparse_output(bool sparse);
  void write_modes(const std::vector<double>& frequencies_hz,
                   const std::vector<Eigen::MatrixXd>& shapes);
  void set_attribute(const std::string& name, double value);
  void set_attribute(const std::string& name, const std::string& value);
  void set_count(const std::string& name, long long value);
  void set_element_nodes(const std::map<int, std::vector<int>>& nodes);
  void end_analysis(const std::string& status = "complete");
  /// Makes every point appended so far complete in the file, for a reader of this process
  /// (live_writers.h); nothing after a failed write.
  void sync_for_reader();

  const std::vector<int>& node_ids() const;
  /// The analyses in the file (those of a continued file included).
  int n_analyses() const;

 private:
  struct Impl;
  std::unique_ptr<Impl> impl_;
};

}  // namespace impactfe
