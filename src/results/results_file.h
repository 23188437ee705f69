#pragma once
/// The results file <jobname>.h5 (HDF5), written as the run goes: every stored time point is
/// appended and flushed, so a run that dies keeps what it finished. Schema: docs/results_file.md.
#include <Eigen/Core>

#include <map>
#include <memory>
#include <optional>
#include <string>
#include <vector>

#include "core/model.h"

namespace impactfe {

/// The layout version of <jobname>.h5 that this program writes (attribute format_version) and
/// the newest it reads.
inline constexpr int kResultsFormatVersion = 2;

/// Element results of one family at one time point: one row per element.
struct ElementResultTable {
  std::vector<int> element_ids;         // fixed for an analysis
  std::vector<std::string> item_names;  // e.g. {"FORC", "SAXL", "EPEL"}
  Eigen::MatrixXd values;               // n_elements x n_items
};

/// One stored time point (or load step of a static run, or expansion time).
/// Nodal arrays are n_nodes x 6 in the node order of the model section of the file
/// (ascending node id), columns UX UY UZ ROTX ROTY ROTZ; NaN where a DOF does not exist or was
/// not computed (e.g. slave DOFs of a reduced run before expansion).
struct TimePoint {
  double time = 0.0;
  int load_step = 1;
  int substep = 1;
  Eigen::MatrixXd displacement;  // U
  /// Imaginary part of U (dataset UI) of a harmonic analysis, whose `time` is the frequency in
  /// Hz and whose U is the real part; empty otherwise.
  Eigen::MatrixXd displacement_imag;
  Eigen::MatrixXd velocity;      // V (NaN for static)
  Eigen::MatrixXd acceleration;  // A (NaN for static)
  Eigen::MatrixXd reaction;      // reaction forces at constrained DOFs, NaN elsewhere
  std::map<std::string, ElementResultTable> element_results;  // by element family
  Eigen::VectorXd gap_forces;  // GP gap-condition forces, input order (reduced / MSUP runs)
  /// Explicit runs with contact: the resultant force (x, y, z) on the contact surface of each
  /// EDCGEN entity, 3 per entity in EDCGEN order (NaN for a single surface).
  Eigen::VectorXd contact_forces;
  /// Explicit runs: kinetic, internal and hourglass energy of each part (EDPART numbers), 3 per
  /// part.
  Eigen::VectorXd part_energies;
  /// Frame acceleration (ACEL) acting at this time point, when the analysis records it (full
  /// runs): a superelement expansion applies its static correction from it.
  std::optional<Eigen::Vector3d> frame_acceleration;
  /// Energy balance: "kinetic", "strain", "external_work", "gap_work", "dissipation",
  /// "plastic_work".
  std::map<std::string, double> energy;
};

/// Kind of an analysis section in the file.
enum class ResultsKind {
  Static,
  Modal,
  Transient,
  ReducedTransient,
  Expansion,
  Substructure,
  Harmonic,
  Spectrum
};
/// "static", "modal", "transient", "reduced_transient", "expansion", "substructure",
/// "harmonic", "spectrum".
const char* results_kind_name(ResultsKind kind);
/// Whether the time points of an analysis of this kind are a history in time: not those of a
/// modal analysis (one per mode, at its frequency: the modes' element results) or of a spectrum
/// analysis (peak responses).
inline bool is_time_history(ResultsKind kind) {
  return kind != ResultsKind::Modal && kind != ResultsKind::Spectrum;
}

/// Energy columns of the per-analysis `energy` dataset, in stored order (docs/results_file.md).
/// "plastic_work" came last (files written before it have 5 columns).
inline constexpr const char* kEnergyNames[6] = {"kinetic",  "strain",      "external_work",
                                                "gap_work", "dissipation", "plastic_work"};

/// Two stored times are the same time point when |a - b| <= 1e-12 * max(1, |a|, |b|).
bool same_time(double a, double b);

/// Row of `node` in the ascending node ids of a results file; -1 when absent.
int node_row(const std::vector<int>& node_ids, int node);

/// Whether a ResultsWriter writes on a thread of its own (results_writer.cpp): Auto when the
/// run may use two threads (--threads) and a core is idle when the writer is created, On
/// whenever HDF5 can be called from two threads, Off never (`impactfe run --results-thread`).
enum class WriterThread { Auto, On, Off };
/// For the writers created from now on.
void set_results_writer_thread(WriterThread mode);

/// Writes <jobname>.h5. One file per job; one /analysis_<k> group per analysis in run order.
/// The writing may run on a thread of its own (WriterThread): a call then hands the operation
/// over and returns; a failure of the file (a full disk) is thrown by the next call.
/// end_analysis returns when the analysis is in the file.
class ResultsWriter {
 public:
  /// Creates the file (under a temporary name, renamed over `path` once it holds the model
  /// section: an existing file is replaced whole) and writes the model section.
  ResultsWriter(const std::string& path, const Model& model);
  /// Opens an existing results file to add analyses after those in it (a run continued from a
  /// restart point, docs/solution_control.md): its model section is kept as written.
  struct Append {};
  ResultsWriter(const std::string& path, Append);
  ~ResultsWriter();
  ResultsWriter(const ResultsWriter&) = delete;
  ResultsWriter& operator=(const ResultsWriter&) = delete;

  /// Opens a new analysis group /analysis_<k>; returns its 1-based index k. Ends the previous
  /// analysis first if it is still open (status "complete"). `expected_points`: the points the
  /// analysis will store when known in advance (0: not known); a small count gives time blocks
  /// of fewer points (result_series::block_rows_for). Storing more is still right.
  int begin_analysis(ResultsKind kind, const std::string& description,
                     long long expected_points = 0);
  /// Appends one time point to the current analysis (written at the file's next sync).
  void append(const TimePoint& point);
  void append(TimePoint&& point);
  /// Whether the points that follow may leave quantities, nodes or elements absent (OUTRES per
  /// item or component, reduced runs): their NaN rows and columns only vanish when compressed,
  /// so every main dataset created from then on is. Dense output (every quantity of every node
  /// and element at every stored point) compresses only datasets of at least
  /// result_series::kMinCompressedPointValues values per point. Default: sparse.
  void set_sparse_output(bool sparse);
  /// Modal results of the current analysis: frequencies (Hz) and mode shapes (each n_nodes x 6).
  void write_modes(const std::vector<double>& frequencies_hz,
                   const std::vector<Eigen::MatrixXd>& shapes);
  /// Free-form scalar attributes of the current analysis (summary numbers, counts).
  void set_attribute(const std::string& name, double value);
  void set_attribute(const std::string& name, const std::string& value);
  /// Integer attribute of the current analysis (counts: DOFs, factorizations, ...).
  void set_count(const std::string& name, long long value);
  /// Replaces the node lists of the given elements in the model section: a superelement's
  /// nodes (its master nodes) are known only once its file is read.
  void set_element_nodes(const std::map<int, std::vector<int>>& nodes);
  /// Marks the current analysis as finished (status attribute "complete" or the error text),
  /// once everything before it is written.
  /// An analysis still open when the writer is destroyed is marked "incomplete"; a killed run
  /// leaves "running".
  void end_analysis(const std::string& status = "complete");

  const std::vector<int>& node_ids() const;
  const std::string& path() const;

 private:
  void register_live();
  struct Impl;
  std::unique_ptr<Impl> impl_;
};

/// Reads a results file for `impactfe post` / `info` and the POST1/POST26 stage.
class ResultsReader {
 public:
  explicit ResultsReader(const std::string& path);
  ~ResultsReader();

  struct AnalysisInfo {
    int index = 0;  // 1-based, the k of /analysis_<k>
    ResultsKind kind = ResultsKind::Static;
    std::string description;
    std::string status;
    int n_time_points = 0;
    double time_first = 0.0;  // first / last stored time (0 when no time point)
    double time_last = 0.0;
    int n_gaps = 0;      // columns of gap_forces
    int n_contacts = 0;  // contact entities of contact_forces (3 columns each)
    int n_parts = 0;     // parts of part_energies (3 columns each)
    int n_modes = 0;     // modal results stored in this analysis
    std::vector<std::string> element_families;
    std::map<std::string, double> numeric_attributes;
    std::map<std::string, std::string> text_attributes;
  };

  /// Element of the model section (node list without the zero padding).
  struct ElementInfo {
    int id = 0;
    std::string type_name;  // ANSYS name, e.g. "LINK8"
    int type = 0;
    int mat = 0;
    int real = 0;
    std::vector<int> nodes;
  };

  const std::string& path() const;
  std::string title() const;
  /// The deck's /UNITS label (SI, BIN, ...); empty when the deck gave none.
  std::string units() const;
  const std::vector<int>& node_ids() const;
  Eigen::MatrixXd node_coordinates() const;  // n_nodes x 3
  const std::vector<ElementInfo>& elements() const;
  std::vector<AnalysisInfo> analyses() const;
  /// Stored times of analysis a (1-based).
  std::vector<double> times(int analysis) const;
  /// (load step, substep) of each stored time point of analysis a (1-based).
  std::vector<std::pair<int, int>> load_steps_of(int analysis) const;

  /// Time series of a nodal quantity: lab in UX..ROTZ, VX VY VZ, AX AY AZ, or reaction FX..MZ.
  /// Returns (time, value) pairs over all analyses in order, only where the value exists; at a
  /// time present in several analyses the later analysis wins.
  std::vector<std::pair<double, double>> nodal_series(int node, const std::string& lab) const;
  /// The imaginary part of a displacement label (UX .. ROTZ) over the harmonic analyses'
  /// frequencies (dataset UI); empty when the file has none.
  std::vector<std::pair<double, double>> nodal_series_imaginary(int node,
                                                                const std::string& lab) const;
  /// Time series of an element item (SAXL, FORC, STAT, ...).
  std::vector<std::pair<double, double>> element_series(int element, const std::string& item) const;
  /// Time series of a GP gap-condition force (1-based gap number).
  std::vector<std::pair<double, double>> gap_force_series(int gap) const;
  /// Time series of the force on the contact surface of an explicit contact entity (1-based,
  /// EDCGEN order), component FX, FY or FZ.
  std::vector<std::pair<double, double>> contact_force_series(int entity,
                                                              const std::string& component) const;
  /// Time series of an explicit run's part energy (part 1-based, EDPART numbers): KE kinetic,
  /// IE internal, HE hourglass.
  std::vector<std::pair<double, double>> part_energy_series(int part,
                                                            const std::string& item) const;
  /// Modal frequencies (Hz) of the last modal analysis; empty when none.
  std::vector<double> frequencies() const;
  /// Damped frequencies and stabilities (Hz) of the last modal analysis (its attributes
  /// damped_frequency_<n>, stability_<n>); empty when it was undamped (only MODOPT,QRDAMP
  /// stores them).
  std::vector<double> damped_frequencies() const;
  std::vector<double> stabilities() const;
  /// Mode shape (n_nodes x 6) of mode 1-based `mode` of the last modal analysis.
  Eigen::MatrixXd mode_shape(int mode) const;
  /// Frequencies (Hz) / mode shape of modal analysis a (1-based); empty / InputError when the
  /// analysis has no modes.
  std::vector<double> frequencies_of(int analysis) const;
  Eigen::MatrixXd mode_shape_of(int analysis, int mode) const;
  /// Full time point k (0-based) of analysis a (1-based). Energies that were not stored are
  /// absent from the map; the element tables hold every family of the analysis.
  TimePoint time_point(int analysis, int k) const;

 private:
  struct Impl;
  std::unique_ptr<Impl> impl_;
};

}  // namespace impactfe
