// Results file round trips: model section, time points, NaN handling, crash safety (flush),
// the series merge rule across analyses, modes, attributes and error messages.
#include <gtest/gtest.h>
#include <hdf5.h>
#include <signal.h>
#include <sys/wait.h>
#include <unistd.h>

#include <cmath>
#include <filesystem>
#include <fstream>
#include <iostream>
#include <limits>
#include <random>
#include <sstream>

#include "../support/stored_chunks.h"
#include "core/errors.h"
#include "core/thread_pool.h"
#include "results/live_writers.h"
#include "results/result_series.h"
#include "results/results_file.h"

namespace impactfe::test_results_file {
namespace {

namespace fs = std::filesystem;
constexpr double kNaN = std::numeric_limits<double>::quiet_NaN();

/// A fresh scratch directory per test, removed afterwards.
class ResultsFileTest : public ::testing::Test {
 protected:
  void SetUp() override {
    const auto* info = ::testing::UnitTest::GetInstance()->current_test_info();
    dir_ = fs::temp_directory_path() /
           (std::string("impactfe_results_") + info->name() + "_" + std::to_string(getpid()));
    fs::remove_all(dir_);
    fs::create_directories(dir_);
  }
  void TearDown() override { fs::remove_all(dir_); }
  std::string file(const std::string& name) const { return (dir_ / name).string(); }
  fs::path dir_;
};

/// Nodes 1, 2, 5 (inserted out of order), a LINK8 (6), a triangular SHELL63 (7), a MASS21 (8).
Model small_model() {
  Model m;
  m.title = "Pendulum test model";
  m.jobname = "pend";
  for (auto [id, x, y] : {std::tuple{5, 0.0, 10.0}, {1, 0.0, 0.0}, {2, 10.0, 0.0}}) {
    Node n;
    n.id = id;
    n.x = Vec3(x, y, 0.5 * id);
    m.nodes[id] = n;
  }
  auto add_type = [&](int id, const char* name) {
    ElementType t;
    t.id = id;
    t.ansys_name = name;
    m.element_types[id] = t;
  };
  add_type(1, "LINK8");
  add_type(2, "SHELL63");
  add_type(3, "MASS21");
  auto add_elem = [&](int id, int type, int mat, int real, std::vector<int> nodes) {
    ElementRecord e;
    e.id = id;
    e.type = type;
    e.mat = mat;
    e.real = real;
    e.nodes = std::move(nodes);
    m.elements[id] = e;
  };
  add_elem(6, 1, 1, 1, {1, 2});
  add_elem(7, 2, 2, 3, {1, 2, 5, 5});
  add_elem(8, 3, 1, 2, {5});
  return m;
}

/// Analytic nodal field: value(node index i, dof j, time t, quantity q).
double field(int i, int j, double t, int q) {
  return 100.0 * q + 10.0 * i + j + 0.25 * t;
}

Eigen::MatrixXd nodal(double t, int q) {
  Eigen::MatrixXd m(3, 6);
  for (int i = 0; i < 3; ++i)
    for (int j = 0; j < 6; ++j) m(i, j) = field(i, j, t, q);
  return m;
}

TimePoint make_point(double t, int step, int sub) {
  TimePoint p;
  p.time = t;
  p.load_step = step;
  p.substep = sub;
  p.displacement = nodal(t, 0);
  p.velocity = nodal(t, 1);
  p.acceleration = nodal(t, 2);
  p.reaction = Eigen::MatrixXd::Constant(3, 6, kNaN);
  p.reaction(0, 0) = -3.0 * t;  // only node 1 UX is constrained
  ElementResultTable spar{{6}, {"FORC", "SAXL"}, Eigen::MatrixXd(1, 2)};
  spar.values << 7.0 * t, 70.0 * t;
  ElementResultTable shell{{7}, {"SX"}, Eigen::MatrixXd::Constant(1, 1, -t)};
  p.element_results = {{"spar", spar}, {"shell", shell}};
  p.gap_forces = Eigen::Vector2d(1.0 + t, 2.0 + t);
  p.energy = {{"kinetic", 0.5 * t}, {"strain", 0.25 * t}};
  return p;
}

void write_three_points(ResultsWriter& w) {
  w.begin_analysis(ResultsKind::Transient, "full transient");
  w.append(make_point(0.0, 1, 1));
  w.append(make_point(0.5, 1, 2));
  w.append(make_point(1.0, 2, 1));
}

void expect_matrix_eq(const Eigen::MatrixXd& got, const Eigen::MatrixXd& want) {
  ASSERT_EQ(got.rows(), want.rows());
  ASSERT_EQ(got.cols(), want.cols());
  for (Eigen::Index i = 0; i < got.rows(); ++i)
    for (Eigen::Index j = 0; j < got.cols(); ++j) {
      if (std::isnan(want(i, j)))
        EXPECT_TRUE(std::isnan(got(i, j))) << i << "," << j;
      else
        EXPECT_EQ(got(i, j), want(i, j)) << i << "," << j;  // float64 stored: bit exact
    }
}

TEST_F(ResultsFileTest, ModelSectionRoundTrip) {
  const Model model = small_model();
  {
    ResultsWriter w(file("m.h5"), model);
    EXPECT_EQ(w.node_ids(), (std::vector<int>{1, 2, 5}));
  }
  ResultsReader r(file("m.h5"));
  EXPECT_EQ(r.title(), "Pendulum test model");
  EXPECT_EQ(r.node_ids(), (std::vector<int>{1, 2, 5}));
  Eigen::MatrixXd xyz(3, 3);
  xyz << 0, 0, 0.5, 10, 0, 1.0, 0, 10, 2.5;
  expect_matrix_eq(r.node_coordinates(), xyz);
  ASSERT_EQ(r.elements().size(), 3u);
  const auto& shell = r.elements()[1];
  EXPECT_EQ(shell.id, 7);
  EXPECT_EQ(shell.type_name, "SHELL63");
  EXPECT_EQ(shell.type, 2);
  EXPECT_EQ(shell.mat, 2);
  EXPECT_EQ(shell.real, 3);
  EXPECT_EQ(shell.nodes, (std::vector<int>{1, 2, 5, 5}));
  EXPECT_EQ(r.elements()[2].type_name, "MASS21");
  EXPECT_EQ(r.elements()[2].nodes, (std::vector<int>{5}));
  EXPECT_TRUE(r.analyses().empty());

  // Schema check with the plain C API: node lists padded with 0 to 8 columns.
  hid_t f = H5Fopen(file("m.h5").c_str(), H5F_ACC_RDONLY, H5P_DEFAULT);
  ASSERT_GE(f, 0);
  hid_t ds = H5Dopen2(f, "model/element_nodes", H5P_DEFAULT);
  ASSERT_GE(ds, 0);
  hid_t space = H5Dget_space(ds);
  hsize_t dims[2] = {0, 0};
  H5Sget_simple_extent_dims(space, dims, nullptr);
  EXPECT_EQ(dims[0], 3u);
  EXPECT_EQ(dims[1], 8u);
  std::vector<int> buf(24);
  H5Dread(ds, H5T_NATIVE_INT, H5S_ALL, H5S_ALL, H5P_DEFAULT, buf.data());
  EXPECT_EQ(buf, (std::vector<int>{1, 2, 0, 0, 0, 0, 0, 0, 1, 2, 5, 5,
                                   0, 0, 0, 0, 5, 0, 0, 0, 0, 0, 0, 0}));
  H5Sclose(space);
  H5Dclose(ds);
  H5Fclose(f);
}

TEST_F(ResultsFileTest, ThreeTimePointsRoundTrip) {
  {
    ResultsWriter w(file("t.h5"), small_model());
    write_three_points(w);
    w.end_analysis();
  }
  ResultsReader r(file("t.h5"));
  auto an = r.analyses();
  ASSERT_EQ(an.size(), 1u);
  EXPECT_EQ(an[0].index, 1);
  EXPECT_EQ(an[0].kind, ResultsKind::Transient);
  EXPECT_EQ(an[0].description, "full transient");
  EXPECT_EQ(an[0].status, "complete");
  EXPECT_EQ(an[0].n_time_points, 3);
  EXPECT_EQ(an[0].time_first, 0.0);
  EXPECT_EQ(an[0].time_last, 1.0);
  EXPECT_EQ(an[0].n_gaps, 2);
  EXPECT_EQ(an[0].element_families, (std::vector<std::string>{"shell", "spar"}));
  EXPECT_EQ(r.times(1), (std::vector<double>{0.0, 0.5, 1.0}));

  for (int k = 0; k < 3; ++k) {
    const double t = 0.5 * k;
    const TimePoint want = make_point(t, 0, 0);
    const TimePoint got = r.time_point(1, k);
    EXPECT_EQ(got.time, t);
    expect_matrix_eq(got.displacement, want.displacement);
    expect_matrix_eq(got.velocity, want.velocity);
    expect_matrix_eq(got.acceleration, want.acceleration);
    expect_matrix_eq(got.reaction, want.reaction);
    expect_matrix_eq(got.gap_forces, want.gap_forces);
    ASSERT_EQ(got.element_results.size(), 2u);
    const auto& spar = got.element_results.at("spar");
    EXPECT_EQ(spar.element_ids, (std::vector<int>{6}));
    EXPECT_EQ(spar.item_names, (std::vector<std::string>{"FORC", "SAXL"}));
    expect_matrix_eq(spar.values, want.element_results.at("spar").values);
    // Only the stored energy terms come back.
    EXPECT_EQ(got.energy,
              (std::map<std::string, double>{{"kinetic", 0.5 * t}, {"strain", 0.25 * t}}));
  }
  EXPECT_EQ(r.time_point(1, 2).load_step, 2);
  EXPECT_EQ(r.time_point(1, 1).substep, 2);

  using S = std::vector<std::pair<double, double>>;
  // Node 2 is index 1: UY = 10 + 1 + 0.25 t; VZ = 100 + 10 + 2 + 0.25 t; AX = 200 + 10 + 0.25 t.
  EXPECT_EQ(r.nodal_series(2, "UY"), (S{{0.0, 11.0}, {0.5, 11.125}, {1.0, 11.25}}));
  EXPECT_EQ(r.nodal_series(2, "vz"), (S{{0.0, 112.0}, {0.5, 112.125}, {1.0, 112.25}}));
  EXPECT_EQ(r.nodal_series(2, "AX"), (S{{0.0, 210.0}, {0.5, 210.125}, {1.0, 210.25}}));
  EXPECT_EQ(r.nodal_series(5, "ROTZ"), (S{{0.0, 25.0}, {0.5, 25.125}, {1.0, 25.25}}));
  EXPECT_EQ(r.nodal_series(1, "FX"), (S{{0.0, -0.0}, {0.5, -1.5}, {1.0, -3.0}}));
  EXPECT_TRUE(r.nodal_series(2, "FX").empty());  // unconstrained: reaction absent everywhere
  EXPECT_EQ(r.element_series(6, "SAXL"), (S{{0.0, 0.0}, {0.5, 35.0}, {1.0, 70.0}}));
  EXPECT_EQ(r.element_series(6, "forc"), (S{{0.0, 0.0}, {0.5, 3.5}, {1.0, 7.0}}));
  EXPECT_EQ(r.element_series(7, "SX"), (S{{0.0, -0.0}, {0.5, -0.5}, {1.0, -1.0}}));
  EXPECT_EQ(r.gap_force_series(2), (S{{0.0, 2.0}, {0.5, 2.5}, {1.0, 3.0}}));
  EXPECT_TRUE(r.frequencies().empty());
}

TEST_F(ResultsFileTest, NaNAndMissingQuantities) {
  {
    ResultsWriter w(file("n.h5"), small_model());
    w.begin_analysis(ResultsKind::Static, "static");
    for (int k = 0; k < 3; ++k) {
      TimePoint p;
      p.time = 1.0 + k;
      p.load_step = k + 1;
      p.displacement = nodal(p.time, 0);
      if (k == 1) p.displacement(2, 2) = kNaN;  // node 5 UZ not computed at t = 2
      // velocity / acceleration / reaction / gaps / energy left empty (static)
      if (k >= 1) {  // element family appears only from the second point on
        ElementResultTable spar{{6}, {"SAXL"}, Eigen::MatrixXd::Constant(1, 1, 10.0 * k)};
        p.element_results["spar"] = spar;
      }
      w.append(p);
    }
  }
  ResultsReader r(file("n.h5"));
  using S = std::vector<std::pair<double, double>>;
  EXPECT_EQ(r.nodal_series(5, "UZ"), (S{{1.0, 22.25}, {3.0, 22.75}}));
  EXPECT_TRUE(r.nodal_series(5, "VX").empty());
  EXPECT_TRUE(r.nodal_series(1, "MZ").empty());
  EXPECT_EQ(r.element_series(6, "SAXL"), (S{{2.0, 10.0}, {3.0, 20.0}}));
  const TimePoint p0 = r.time_point(1, 0);
  EXPECT_TRUE(p0.velocity.array().isNaN().all());
  EXPECT_EQ(p0.velocity.rows(), 3);
  EXPECT_TRUE(std::isnan(p0.element_results.at("spar").values(0, 0)));
  EXPECT_EQ(p0.gap_forces.size(), 0);
  EXPECT_TRUE(p0.energy.empty());
  // The writer was destroyed without end_analysis.
  EXPECT_EQ(r.analyses()[0].status, "incomplete");
}

/// Reads the three points written by write_three_points from `path`.
void expect_three_points(const std::string& path) {
  ResultsReader r(path);
  ASSERT_EQ(r.analyses().size(), 1u);
  EXPECT_EQ(r.analyses()[0].status, "running");
  EXPECT_EQ(r.times(1), (std::vector<double>{0.0, 0.5, 1.0}));
  using S = std::vector<std::pair<double, double>>;
  EXPECT_EQ(r.nodal_series(2, "UY"), (S{{0.0, 11.0}, {0.5, 11.125}, {1.0, 11.25}}));
  EXPECT_EQ(r.element_series(6, "SAXL"), (S{{0.0, 0.0}, {0.5, 35.0}, {1.0, 70.0}}));
  EXPECT_EQ(r.gap_force_series(1), (S{{0.0, 1.0}, {0.5, 1.5}, {1.0, 2.0}}));
}

TEST_F(ResultsFileTest, AppendedPointsAreOnDiskBeforeClose) {
  ResultsWriter w(file("live.h5"), small_model());
  write_three_points(w);
  // The writer is still open: after a sync (every 64 points or 0.1 s, or when a reader of this
  // process opens the file) a byte copy of the file must already be a complete file.
  sync_live_writer(file("live.h5"));
  fs::copy_file(file("live.h5"), file("copy.h5"));
  expect_three_points(file("copy.h5"));
  // A reader in the same process (post stage while the writer lives) sees the same points.
  expect_three_points(file("live.h5"));
  w.append(make_point(1.5, 2, 2));
  EXPECT_EQ(ResultsReader(file("live.h5")).times(1).size(), 4u);
}

TEST_F(ResultsFileTest, KilledRunKeepsAppendedPoints) {
  const std::string path = file("killed.h5");
  pid_t pid = fork();
  ASSERT_GE(pid, 0);
  if (pid == 0) {
    ResultsWriter w(path, small_model());
    write_three_points(w);
    sync_live_writer(path);
    w.append(make_point(1.5, 2, 2));  // after the last sync: lost, never half there
    raise(SIGKILL);                   // no destructors, no HDF5 shutdown
    _exit(3);
  }
  int status = 0;
  waitpid(pid, &status, 0);
  ASSERT_TRUE(WIFSIGNALED(status));
  expect_three_points(path);
}

TEST_F(ResultsFileTest, ReaderOpensFileOfRunningJobInAnotherProcess) {
  const std::string path = file("running.h5");
  int ready[2];
  ASSERT_EQ(pipe(ready), 0);
  pid_t pid = fork();
  ASSERT_GE(pid, 0);
  if (pid == 0) {
    close(ready[0]);
    alarm(30);                             // never outlive a broken parent
    ResultsWriter w(path, small_model());  // holds the HDF5 file lock while it lives
    write_three_points(w);
    sync_live_writer(path);  // what the writer does every 64 points or 0.1 s
    char c = 1;
    if (write(ready[1], &c, 1) != 1) _exit(2);
    pause();  // keep the file open until killed
    _exit(0);
  }
  close(ready[1]);
  struct KillChild {  // also when the reader throws
    pid_t pid;
    ~KillChild() {
      kill(pid, SIGKILL);
      waitpid(pid, nullptr, 0);
    }
  } guard{pid};
  char c = 0;
  ASSERT_EQ(read(ready[0], &c, 1), 1);
  close(ready[0]);
  expect_three_points(path);  // `impactfe info` on a running job
}

TEST_F(ResultsFileTest, MergeRuleReducedThenExpansion) {
  {
    ResultsWriter w(file("merge.h5"), small_model());
    // Reduced run: node 2 UX is a master, node 5 UX a slave (not computed).
    w.begin_analysis(ResultsKind::ReducedTransient, "reduced");
    for (int k = 0; k < 4; ++k) {
      TimePoint p;
      p.time = 0.1 * k;
      p.displacement = Eigen::MatrixXd::Constant(3, 6, kNaN);
      p.displacement(1, 0) = 1.0 + k;  // 1 2 3 4
      w.append(p);
    }
    w.end_analysis();
    // Expansion at t = 0.1 and t = 0.3 (slightly off, within 1e-12 relative).
    w.begin_analysis(ResultsKind::Expansion, "expansion");
    const double times[2] = {0.1, 0.3 + 1e-14};
    for (int k = 0; k < 2; ++k) {
      TimePoint p;
      p.time = times[k];
      p.displacement = Eigen::MatrixXd::Constant(3, 6, kNaN);
      p.displacement(1, 0) = k == 0 ? 20.0 : kNaN;  // NaN: the earlier value must survive
      p.displacement(2, 0) = 50.0 + k;
      w.append(p);
    }
    w.end_analysis();
  }
  ResultsReader r(file("merge.h5"));
  ASSERT_EQ(r.analyses().size(), 2u);
  EXPECT_EQ(r.analyses()[1].kind, ResultsKind::Expansion);
  auto node2 = r.nodal_series(2, "UX");
  ASSERT_EQ(node2.size(), 4u);
  EXPECT_DOUBLE_EQ(node2[0].second, 1.0);
  EXPECT_DOUBLE_EQ(node2[1].first, 0.1);
  EXPECT_DOUBLE_EQ(node2[1].second, 20.0);  // expansion replaces the reduced value
  EXPECT_DOUBLE_EQ(node2[2].second, 3.0);
  EXPECT_DOUBLE_EQ(node2[3].second, 4.0);  // expansion had no value at 0.3
  for (std::size_t i = 1; i < node2.size(); ++i) EXPECT_LT(node2[i - 1].first, node2[i].first);
  auto node5 = r.nodal_series(5, "UX");
  ASSERT_EQ(node5.size(), 2u);
  EXPECT_DOUBLE_EQ(node5[0].first, 0.1);
  EXPECT_DOUBLE_EQ(node5[0].second, 50.0);
  EXPECT_DOUBLE_EQ(node5[1].second, 51.0);
}

TEST_F(ResultsFileTest, ModesAndAttributes) {
  std::vector<Eigen::MatrixXd> shapes = {nodal(0.0, 3), nodal(4.0, 4)};
  shapes[1](0, 5) = kNaN;
  {
    ResultsWriter w(file("modal.h5"), small_model());
    EXPECT_EQ(w.begin_analysis(ResultsKind::Modal, "modes"), 1);
    w.write_modes({1.5, 12.25}, shapes);
    w.set_attribute("n_modes_requested", 2.0);
    w.set_attribute("method", "LANB");
    w.end_analysis();
    EXPECT_EQ(w.begin_analysis(ResultsKind::Static, "after"), 2);
    w.end_analysis("solution failed: singular matrix");
  }
  ResultsReader r(file("modal.h5"));
  EXPECT_EQ(r.frequencies(), (std::vector<double>{1.5, 12.25}));
  expect_matrix_eq(r.mode_shape(1), shapes[0]);
  expect_matrix_eq(r.mode_shape(2), shapes[1]);
  auto an = r.analyses();
  ASSERT_EQ(an.size(), 2u);
  EXPECT_EQ(an[0].kind, ResultsKind::Modal);
  EXPECT_EQ(an[0].n_modes, 2);
  EXPECT_EQ(an[0].n_time_points, 0);
  EXPECT_EQ(an[0].numeric_attributes, (std::map<std::string, double>{{"n_modes_requested", 2.0}}));
  EXPECT_EQ(an[0].text_attributes, (std::map<std::string, std::string>{{"method", "LANB"}}));
  EXPECT_EQ(an[1].status, "solution failed: singular matrix");
  try {
    r.mode_shape(3);
    FAIL() << "expected InputError";
  } catch (const InputError& e) {
    EXPECT_STREQ(e.what(), "mode 3 does not exist (the results file has modes 1..2)");
  }
}

/// Expects an InputError without location whose message contains `part`.
template <typename F>
void expect_input_error(F f, const std::string& part) {
  try {
    f();
    ADD_FAILURE() << "expected InputError containing: " << part;
  } catch (const InputError& e) {
    EXPECT_FALSE(e.where().known());
    EXPECT_EQ(std::string(e.what()), e.message());
    EXPECT_NE(e.message().find(part), std::string::npos) << e.message();
  }
}

/// A results file that cannot be created ends the run with exit status 2 and the reason.
void expect_cannot_create(const std::string& path) {
  try {
    ResultsWriter w(path, small_model());
    ADD_FAILURE() << "expected SolutionError";
  } catch (const SolutionError& e) {
    EXPECT_NE(e.message().find("cannot create results file"), std::string::npos) << e.message();
    EXPECT_NE(e.message().find("No such file or directory"), std::string::npos) << e.message();
  }
}

TEST_F(ResultsFileTest, ErrorMessages) {
  expect_input_error([&] { ResultsReader r(file("none.h5")); },
                     "results file '" + file("none.h5") + "' does not exist");
  std::ofstream(file("text.h5")) << "not hdf5\n";
  expect_input_error([&] { ResultsReader r(file("text.h5")); }, "is not an impactfe results file");
  expect_cannot_create(file("no_dir/x.h5"));
  {
    ResultsWriter w(file("e.h5"), small_model());
    write_three_points(w);
  }
  ResultsReader r(file("e.h5"));
  expect_input_error([&] { r.nodal_series(99, "UX"); }, "node 99 is not in results file");
  expect_input_error([&] { r.nodal_series(2, "UQ"); }, "unknown nodal result label 'UQ'");
  expect_input_error([&] { r.element_series(42, "SAXL"); }, "element 42 is not in results file");
  expect_input_error([&] { r.element_series(6, "SEQV"); },
                     "element item 'SEQV' is not stored for element 6 (available: FORC SAXL)");
  expect_input_error([&] { r.element_series(8, "SAXL"); },
                     "no element results are stored for element 8");
  expect_input_error([&] { r.gap_force_series(3); },
                     "gap 3 does not exist (the results file has gaps 1..2)");
  expect_input_error([&] { r.time_point(2, 0); }, "has no analysis 2 (it has 1)");
  expect_input_error([&] { r.time_point(1, 3); }, "analysis 1 has no time point 3 (it has 3)");
  expect_input_error([&] { r.mode_shape(1); }, "no mode shapes are stored");
}

TEST_F(ResultsFileTest, ModelWithoutElements) {
  Model m;
  m.title = "nodes only";
  Node n;
  n.id = 3;
  m.nodes[3] = n;
  {
    ResultsWriter w(file("empty.h5"), m);
    w.begin_analysis(ResultsKind::Static, "");
    TimePoint p;
    p.displacement = Eigen::MatrixXd::Zero(1, 6);
    w.append(p);
    w.end_analysis();
  }
  ResultsReader r(file("empty.h5"));
  EXPECT_TRUE(r.elements().empty());
  EXPECT_EQ(r.nodal_series(3, "UZ"), (std::vector<std::pair<double, double>>{{0.0, 0.0}}));
}

/// Bytes this process has read through read()/pread() so far (/proc/self/io rchar).
long long bytes_read_so_far() {
  std::ifstream io("/proc/self/io");
  std::string key;
  long long value = 0;
  while (io >> key >> value)
    if (key == "rchar:") return value;
  return -1;
}

/// A 190-node model without elements (the helmet's size class).
Model nodes_only(int n) {
  Model m;
  m.title = "long history";
  for (int i = 1; i <= n; ++i) {
    Node node;
    node.id = i;
    node.x = Vec3(i, 0, 0);
    m.nodes[i] = node;
  }
  return m;
}

double history_value(int node_row, int step) {
  return std::sin(1e-3 * step * (node_row + 1)) + 1e-6 * node_row;
}

void append_history(ResultsWriter& w, int n_nodes, int first, int last) {
  for (int k = first; k < last; ++k) {
    TimePoint p;
    p.time = 1e-4 * k;
    p.displacement = Eigen::MatrixXd::Zero(n_nodes, 6);
    for (int i = 0; i < n_nodes; ++i) p.displacement(i, 2) = history_value(i, k);
    w.append(p);
  }
}

void expect_history(const ResultsReader& r, int node, int n_steps) {
  const auto s = r.nodal_series(node, "UZ");
  ASSERT_EQ(s.size(), static_cast<std::size_t>(n_steps));
  for (int k = 0; k < n_steps; k += 97) EXPECT_EQ(s[k].second, history_value(node - 1, k)) << k;
  EXPECT_EQ(s.back().second, history_value(node - 1, n_steps - 1));
}

TEST_F(ResultsFileTest, NodeHistoryOfLongRunReadsFewChunks) {
  constexpr int kNodes = 190, kSteps = 3000;
  const std::string path = file("long.h5");
  {
    ResultsWriter w(path, nodes_only(kNodes));
    w.begin_analysis(ResultsKind::Transient, "long");
    append_history(w, kNodes, 0, kSteps);
    // Still being written: the last points (3000 mod the block rows) are in the staging
    // datasets.
    expect_history(ResultsReader(path), 95, kSteps);
    w.end_analysis();
  }
  const auto file_size = static_cast<long long>(fs::file_size(path));

  // Chunks of U, and how many of them hold node 95's rows.
  hid_t f = H5Fopen(path.c_str(), H5F_ACC_RDONLY, H5P_DEFAULT);
  ASSERT_GE(f, 0);
  hid_t ds = H5Dopen2(f, "analysis_1/U", H5P_DEFAULT);
  hid_t space = H5Dget_space(ds);
  hsize_t n_chunks = 0;
  ASSERT_GE(H5Dget_num_chunks(ds, space, &n_chunks), 0);
  hid_t dcpl = H5Dget_create_plist(ds);
  hsize_t chunk[3] = {0, 0, 0};
  ASSERT_EQ(H5Pget_chunk(dcpl, 3, chunk), 3);
  int touched = 0;
  for (hsize_t c = 0; c < n_chunks; ++c) {
    hsize_t offset[3];
    unsigned mask = 0;
    haddr_t addr = 0;
    hsize_t size = 0;
    ASSERT_GE(H5Dget_chunk_info(ds, space, c, offset, &mask, &addr, &size), 0);
    touched += offset[1] <= 94 && 94 < offset[1] + chunk[1];
  }
  H5Pclose(dcpl);
  H5Sclose(space);
  H5Dclose(ds);
  H5Fclose(f);
  constexpr hsize_t kBlock = result_series::kMaxBlockRows;
  EXPECT_EQ(chunk[0], kBlock);                         // time-blocked chunks
  EXPECT_EQ(touched, (kSteps + kBlock - 1) / kBlock);  // one per block of kBlock points
  EXPECT_GE(n_chunks, 8u * touched);                   // of at least 8 times as many

  // Bytes actually read for one history, measured by the kernel.
  ResultsReader r(path);
  const long long before = bytes_read_so_far();
  ASSERT_GE(before, 0);
  expect_history(r, 95, kSteps);
  const long long read = bytes_read_so_far() - before;
  EXPECT_LT(read, file_size / 5) << read << " of " << file_size << " bytes";
  std::cout << "node history of " << kSteps << " points: read " << read << " of " << file_size
            << " bytes\n";
}

/// An analysis that says how many points it stores gets time blocks that fit them: a smaller
/// file with the same values; storing more than it said still keeps every point.
TEST_F(ResultsFileTest, AnalysisOfKnownPointCountStoresBlocksThatFitThem) {
  constexpr int kNodes = 40;
  struct Run {
    const char* name;
    long long expected;  // told to begin_analysis
    int stored;          // points appended
    hsize_t block;       // time chunk expected
  };
  for (const Run& run :
       {Run{"unknown.h5", 0, 3, result_series::kMaxBlockRows}, Run{"three.h5", 3, 3, 4},
        Run{"five.h5", 5, 5, 8}, Run{"more_than_said.h5", 3, 11, 4}}) {
    const std::string path = file(run.name);
    {
      ResultsWriter w(path, nodes_only(kNodes));
      w.begin_analysis(ResultsKind::Transient, "known count", run.expected);
      w.set_sparse_output(false);  // every item at every point (uniform OUTRES)
      append_history(w, kNodes, 0, run.stored);
      w.end_analysis();
    }
    EXPECT_EQ(testing::stored_layout(path, "analysis_1/U").chunk.at(0), run.block) << run.name;
    const ResultsReader r(path);
    for (int node : {1, 17, kNodes}) {
      const auto s = r.nodal_series(node, "UZ");
      ASSERT_EQ(s.size(), static_cast<std::size_t>(run.stored)) << run.name;
      for (int k = 0; k < run.stored; ++k)
        EXPECT_EQ(s[static_cast<std::size_t>(k)].second, history_value(node - 1, k))
            << run.name << " node " << node << " point " << k;
    }
  }
  // The unwritten rows of a block are stored too (uncompressed, as a dense output's few
  // values per point are): U of 3 points in blocks of 4 takes a tenth of U in blocks of 64.
  EXPECT_LT(10 * testing::stored_layout(file("three.h5"), "analysis_1/U").bytes,
            testing::stored_layout(file("unknown.h5"), "analysis_1/U").bytes);
}

/// The node dimension of a main chunk is split into equal parts (a chunk past the dataset's edge
/// is filled whole by HDF5 before each write): 68 nodes, as the thesis helmet has, whose 64
/// points of U fit 21 nodes in a chunk of 64 kB, take 4 chunks of 17 nodes, not 3 of 21 and one
/// of 5; and the values read back.
TEST_F(ResultsFileTest, MainChunksSplitTheNodesIntoEqualParts) {
  for (int n_nodes : {68, 21, 22, 500}) {
    const std::string path = file("nodes_" + std::to_string(n_nodes) + ".h5");
    constexpr int kPoints = 70;
    {
      ResultsWriter w(path, nodes_only(n_nodes));
      w.begin_analysis(ResultsKind::Transient, "equal parts");
      w.set_sparse_output(false);
      append_history(w, n_nodes, 0, kPoints);
      w.end_analysis();
    }
    const std::vector<hsize_t> chunk = testing::stored_layout(path, "analysis_1/U").chunk;
    ASSERT_EQ(chunk.size(), 3u);
    const hsize_t fit = 64 * 1024 / (result_series::kMaxBlockRows * 6 * 8);  // 21 nodes
    const hsize_t parts = (n_nodes + fit - 1) / fit;                         // fewest chunks
    EXPECT_EQ((n_nodes + chunk[1] - 1) / chunk[1], parts) << n_nodes << " nodes";
    EXPECT_LT(parts * chunk[1] - n_nodes, parts) << n_nodes << " nodes: chunks of " << chunk[1];
    const ResultsReader r(path);
    for (int node : {1, n_nodes / 2, n_nodes}) {
      const auto series = r.nodal_series(node, "UZ");
      ASSERT_EQ(series.size(), static_cast<std::size_t>(kPoints));
      for (int k = 0; k < kPoints; ++k)
        EXPECT_EQ(series[static_cast<std::size_t>(k)].second, history_value(node - 1, k));
    }
  }
}

/// Raw stored bytes of every chunk of a dataset of a results file, in chunk order.
std::vector<std::vector<unsigned char>> stored_chunks(const std::string& path,
                                                      const std::string& dataset) {
  hid_t f = H5Fopen(path.c_str(), H5F_ACC_RDONLY, H5P_DEFAULT);
  hid_t ds = H5Dopen2(f, dataset.c_str(), H5P_DEFAULT);
  std::vector<std::vector<unsigned char>> chunks;
  for (auto& c : testing::stored_chunks(ds)) chunks.push_back(std::move(c.bytes));
  H5Dclose(ds);
  H5Fclose(f);
  return chunks;
}

/// The finished blocks of a compressed series are deflated on a worker thread when the run may
/// use two (issue 11): the file is the same, chunk for chunk, as with one thread, and a reader
/// opening it while a block is being compressed reads that block from the staging rows.
TEST_F(ResultsFileTest, BlocksCompressedOnAWorkerThreadAreStoredAsOnOne) {
  constexpr int kNodes = 700;  // chunks of U of 64 x 21 x 6 values: deflated
  constexpr int kBlock = static_cast<int>(result_series::kMaxBlockRows);
  constexpr int kSteps = 3 * kBlock + 5;
  const int threads_before = threads::max_threads();
  std::vector<std::vector<std::vector<unsigned char>>> stored;
  for (int n_threads : {1, 2}) {
    threads::set_max_threads(n_threads);
    const std::string path = file("threads" + std::to_string(n_threads) + ".h5");
    {
      ResultsWriter w(path, nodes_only(kNodes));
      w.begin_analysis(ResultsKind::Transient, "compressed blocks");
      append_history(w, kNodes, 0, kBlock);  // the first block: submitted to the compressor
      expect_history(ResultsReader(path), 95, kBlock);
      append_history(w, kNodes, kBlock, kSteps);
      expect_history(ResultsReader(path), 95, kSteps);
      w.end_analysis();
    }
    expect_history(ResultsReader(path), 95, kSteps);
    expect_history(ResultsReader(path), kNodes, kSteps);
    stored.push_back(stored_chunks(path, "analysis_1/U"));
  }
  threads::set_max_threads(threads_before);
  EXPECT_EQ(stored[0].size(), 4u * ((kNodes + 20) / 21));  // 4 blocks of 34 chunks
  EXPECT_TRUE(stored[0] == stored[1]);
}

/// Sets how the writers of a test write (WriterThread), and restores the default after it.
struct WriterThreadMode {
  explicit WriterThreadMode(WriterThread mode) { set_results_writer_thread(mode); }
  ~WriterThreadMode() { set_results_writer_thread(WriterThread::Auto); }
};

/// A results file written on a thread of its own (issue 11) is the file written on the
/// caller's: every chunk of U stored as the same bytes. The writer keeps its own copy of the
/// model section (the model may go at once), a reader of this process opening the file
/// mid-run sees every point appended so far, and the analysis is complete in the file when
/// end_analysis returns.
TEST_F(ResultsFileTest, WriterThreadWritesTheSameFileAsTheCallersThread) {
  constexpr int kNodes = 700;  // chunks of U of 64 x 21 x 6 values: deflated
  constexpr int kBlock = static_cast<int>(result_series::kMaxBlockRows);
  constexpr int kSteps = 2 * kBlock + 7;
  std::vector<std::vector<std::vector<unsigned char>>> stored;
  for (WriterThread mode : {WriterThread::Off, WriterThread::On}) {
    const WriterThreadMode set(mode);
    const std::string path = file(mode == WriterThread::On ? "on.h5" : "off.h5");
    {
      auto model = std::make_unique<Model>(nodes_only(kNodes));
      ResultsWriter w(path, *model);
      model.reset();
      w.begin_analysis(ResultsKind::Transient, "writer thread");
      append_history(w, kNodes, 0, kBlock + 3);
      expect_history(ResultsReader(path), 95, kBlock + 3);
      append_history(w, kNodes, kBlock + 3, kSteps);
      w.set_count("substeps", kSteps);
      w.end_analysis();
      const auto info = ResultsReader(path).analyses().at(0);
      EXPECT_EQ(info.status, "complete");
      EXPECT_EQ(info.numeric_attributes.at("substeps"), kSteps);
    }
    expect_history(ResultsReader(path), kNodes, kSteps);
    stored.push_back(stored_chunks(path, "analysis_1/U"));
  }
  EXPECT_EQ(stored[0].size(), 3u * ((kNodes + 20) / 21));  // 3 blocks of 34 chunks
  EXPECT_TRUE(stored[0] == stored[1]);
}

/// A reader of this process opened right after the writer is made (a deck's POST1 after its
/// SOLVE) finds the file: the writer thread creates it under a temporary name and renames it
/// into place, and the reader waits for the writer before it looks for the file.
TEST_F(ResultsFileTest, ReaderRightAfterTheWriterThreadStartsFindsTheFile) {
  const WriterThreadMode set(WriterThread::On);
  for (int k = 0; k < 5; ++k) {
    const std::string path = file("at_once_" + std::to_string(k) + ".h5");
    ResultsWriter w(path, small_model());
    EXPECT_NO_THROW(EXPECT_EQ(ResultsReader(path).node_ids().size(), 3u));
  }
}

/// A failure on the writer thread is thrown by the analysis's next call that waits for the
/// writer (end_analysis) and by every call after it; the points synced before it stay
/// readable. A file that cannot be created is reported by the constructor, as on one thread.
TEST_F(ResultsFileTest, WriterThreadFailureIsThrownByTheNextCall) {
  const WriterThreadMode set(WriterThread::On);
  expect_cannot_create(file("no_dir/x.h5"));
  const std::string path = file("failed.h5");
  {
    ResultsWriter w(path, small_model());
    write_three_points(w);
    sync_live_writer(path);  // the three points complete in the file
    TimePoint bad = make_point(1.5, 2, 2);
    bad.displacement = Eigen::MatrixXd::Zero(2, 6);  // two rows for three nodes
    w.append(std::move(bad));                        // handed over: fails on the writer thread
    EXPECT_THROW(w.end_analysis(), InternalError);
    EXPECT_THROW(w.append(make_point(2.0, 2, 3)), InternalError);
    EXPECT_THROW(w.set_count("substeps", 4), InternalError);
  }
  expect_three_points(path);
}

/// A run killed after a block went to the compressor, before its chunks were written, keeps
/// every point: the block is still read from the staging rows (recent/first_row moves past a
/// block only once its main chunks are flushed).
TEST_F(ResultsFileTest, KilledRunWhileABlockIsCompressedKeepsEveryPoint) {
  constexpr int kNodes = 700;
  constexpr int kBlock = static_cast<int>(result_series::kMaxBlockRows);
  const std::string path = file("killed_block.h5");
  pid_t pid = fork();
  ASSERT_GE(pid, 0);
  if (pid == 0) {
    threads::set_max_threads(2);
    // On the caller's thread: the points handed to a writer thread and not yet written when
    // the run is killed are lost like those after the last sync.
    set_results_writer_thread(WriterThread::Off);
    ResultsWriter w(path, nodes_only(kNodes));
    w.begin_analysis(ResultsKind::Transient, "killed while compressing");
    append_history(w, kNodes, 0, kBlock + 3);  // block 1 submitted at its last point
    sync_live_writer(path);                    // its chunks written, the 3 new points staged
    append_history(w, kNodes, kBlock + 3, 2 * kBlock);  // block 2 submitted, not yet written
    raise(SIGKILL);
    _exit(3);
  }
  int status = 0;
  waitpid(pid, &status, 0);
  ASSERT_TRUE(WIFSIGNALED(status));
  ResultsReader r(path);
  EXPECT_EQ(r.analyses().at(0).status, "running");
  expect_history(r, 95, 2 * kBlock);
  expect_history(r, kNodes, 2 * kBlock);
}

/// Byte offset of the first chunk of a dataset.
haddr_t first_chunk_address(const std::string& path, const std::string& dataset) {
  hid_t f = H5Fopen(path.c_str(), H5F_ACC_RDONLY, H5P_DEFAULT);
  hid_t ds = H5Dopen2(f, dataset.c_str(), H5P_DEFAULT);
  hid_t space = H5Dget_space(ds);
  hsize_t offset[3];
  unsigned mask = 0;
  haddr_t addr = HADDR_UNDEF;
  hsize_t size = 0;
  H5Dget_chunk_info(ds, space, 0, offset, &mask, &addr, &size);
  H5Sclose(space);
  H5Dclose(ds);
  H5Fclose(f);
  return addr;
}

void overwrite(const std::string& path, long long at, const std::string& bytes) {
  std::fstream f(path, std::ios::in | std::ios::out | std::ios::binary);
  f.seekp(at);
  f.write(bytes.data(), static_cast<std::streamsize>(bytes.size()));
}

TEST_F(ResultsFileTest, CorruptedDataIsReportedNotReturned) {
  {
    ResultsWriter w(file("c.h5"), small_model());
    write_three_points(w);
  }
  const haddr_t u = first_chunk_address(file("c.h5"), "analysis_1/U");
  const haddr_t xyz = first_chunk_address(file("c.h5"), "model/node_coordinates");
  ASSERT_NE(u, HADDR_UNDEF);
  fs::copy_file(file("c.h5"), file("c_model.h5"));
  overwrite(file("c.h5"), static_cast<long long>(u) + 20, "\x7f\x13");
  ResultsReader r(file("c.h5"));
  expect_input_error([&] { r.nodal_series(2, "UY"); }, "is damaged or incomplete");
  expect_input_error([&] { r.time_point(1, 0); }, "is damaged or incomplete");
  // Unharmed quantities still read.
  EXPECT_EQ(r.element_series(6, "SAXL").size(), 3u);
  overwrite(file("c_model.h5"), static_cast<long long>(xyz) + 3, "\x01");
  expect_input_error([&] { ResultsReader bad(file("c_model.h5")); }, "is damaged or incomplete");
}

/// Everything a reader returns for the file of write_three_points, as text.
std::string read_everything(const std::string& path) {
  ResultsReader r(path);
  std::string out = r.title();
  for (int n : r.node_ids()) out += " " + std::to_string(n);
  for (const auto& e : r.elements()) out += " " + e.type_name;
  for (const auto& a : r.analyses()) {
    out += " " + a.status + std::to_string(a.n_time_points);
    for (int k = 0; k < a.n_time_points; ++k) {
      const TimePoint p = r.time_point(a.index, k);
      std::ostringstream s;
      s << p.time << p.load_step << p.substep << p.displacement << p.velocity << p.acceleration
        << p.reaction << p.gap_forces;
      for (const auto& [name, t] : p.element_results) s << name << t.values;
      for (const auto& [name, v] : p.energy) s << name << v;
      out += s.str();
    }
  }
  for (const char* lab : {"UX", "VY", "FX"}) {
    for (const auto& [t, v] : r.nodal_series(2, lab)) out += std::to_string(t + v);
  }
  return out;
}

TEST_F(ResultsFileTest, RandomCorruptionNeverGivesWrongNumbersOrACrash) {
  const std::string path = file("r.h5");
  {
    ResultsWriter w(path, small_model());
    write_three_points(w);
  }
  const std::string reference = read_everything(path);
  const auto size = static_cast<long long>(fs::file_size(path));
  std::mt19937 rng(12345);
  int reported = 0, unharmed = 0;
  constexpr int kTrials = 80;  // ~0.2 s each (a process per trial)
  for (int trial = 0; trial < kTrials; ++trial) {
    const std::string bad = file("bad.h5");
    fs::copy_file(path, bad, fs::copy_options::overwrite_existing);
    const long long at = std::uniform_int_distribution<long long>(0, size - 8)(rng);
    std::string bytes(8, '\0');
    for (auto& b : bytes) b = static_cast<char>(rng());
    overwrite(bad, at, bytes);
    // A child process reads, so that a crash is seen as one.
    pid_t pid = fork();
    ASSERT_GE(pid, 0);
    if (pid == 0) {
      alarm(20);
      int code = 3;
      try {
        code = read_everything(bad) == reference ? 0 : 2;
      } catch (const InputError&) {
        code = 1;
      } catch (...) {
        code = 3;
      }
      _exit(code);
    }
    int status = 0;
    waitpid(pid, &status, 0);
    ASSERT_TRUE(WIFEXITED(status))
        << "reader crashed (signal " << WTERMSIG(status) << ") with 8 bytes overwritten at " << at;
    const int code = WEXITSTATUS(status);
    EXPECT_NE(code, 2) << "wrong numbers returned with 8 bytes overwritten at " << at
                       << " (seed trial " << trial << ")";
    EXPECT_NE(code, 3) << "an exception other than InputError with bytes overwritten at " << at;
    reported += code == 1;
    unharmed += code == 0;
  }
  std::cout << kTrials << " corrupted copies: " << reported << " reported, " << unharmed
            << " unharmed (bytes in unused space)\n";
  EXPECT_GT(reported, kTrials / 5);
}

TEST_F(ResultsFileTest, TruncatedFileIsReportedNotACrash) {
  const std::string path = file("t.h5");
  {
    ResultsWriter w(path, small_model());
    write_three_points(w);
  }
  const auto size = static_cast<long long>(fs::file_size(path));
  for (long long keep : {size - 1, size / 2, 2048LL, 100LL}) {
    fs::copy_file(path, file("cut.h5"), fs::copy_options::overwrite_existing);
    fs::resize_file(file("cut.h5"), static_cast<std::uintmax_t>(keep));
    try {
      read_everything(file("cut.h5"));
      ADD_FAILURE() << "a file cut to " << keep << " of " << size << " bytes was read";
    } catch (const InputError& e) {
      const std::string what = e.what();
      EXPECT_TRUE(what.find("truncated") != std::string::npos ||
                  what.find("not an impactfe results file") != std::string::npos ||
                  what.find("damaged") != std::string::npos)
          << what;
    }
  }
}

TEST(ResultsKindTest, NamesAndSameTime) {
  EXPECT_STREQ(results_kind_name(ResultsKind::ReducedTransient), "reduced_transient");
  EXPECT_STREQ(results_kind_name(ResultsKind::Expansion), "expansion");
  EXPECT_TRUE(same_time(1.0, 1.0 + 0.9e-12));
  EXPECT_FALSE(same_time(1.0, 1.0 + 1.1e-12));
  EXPECT_TRUE(same_time(1e6, 1e6 + 0.9e-6));  // relative for |t| > 1
  EXPECT_FALSE(same_time(0.0, 2e-12));        // absolute 1e-12 near zero
}

}  // namespace
}  // namespace impactfe::test_results_file
