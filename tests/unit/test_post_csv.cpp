// Post queries (`impactfe post` / `info`) and the VTU/PVD export, on small hand-built files.
#include <gtest/gtest.h>
#include <unistd.h>

#include <cstdlib>
#include <filesystem>
#include <fstream>
#include <limits>
#include <regex>
#include <sstream>

#include "core/errors.h"
#include "results/post_csv.h"
#include "results/results_file.h"
#include "results/vtk_export.h"

namespace impactfe::test_post_csv {
namespace {

namespace fs = std::filesystem;
constexpr double kNaN = std::numeric_limits<double>::quiet_NaN();

class PostTest : public ::testing::Test {
 protected:
  void SetUp() override {
    const auto* info = ::testing::UnitTest::GetInstance()->current_test_info();
    dir_ = fs::temp_directory_path() /
           (std::string("impactfe_post_") + info->name() + "_" + std::to_string(getpid()));
    fs::remove_all(dir_);
    fs::create_directories(dir_);
  }
  void TearDown() override {
    if (!std::getenv("IMPACTFE_KEEP_TEST_FILES")) fs::remove_all(dir_);
  }
  std::string file(const std::string& name) const { return (dir_ / name).string(); }
  fs::path dir_;
};

/// Nodes 1, 2, 5; LINK8 element 6 (1-2), SHELL63 element 7 (1-2-5-5, a triangle), MASS21 8 (5).
Model small_model() {
  Model m;
  m.title = "post test";
  for (auto [id, x, y] : {std::tuple{1, 0.0, 0.0}, {2, 10.0, 0.0}, {5, 0.0, 10.0}}) {
    Node n;
    n.id = id;
    n.x = Vec3(x, y, 0.0);
    m.nodes[id] = n;
  }
  const char* names[] = {"LINK8", "SHELL63", "MASS21"};
  for (int t = 1; t <= 3; ++t) {
    ElementType et;
    et.id = t;
    et.ansys_name = names[t - 1];
    m.element_types[t] = et;
  }
  auto add = [&](int id, int type, std::vector<int> nodes) {
    ElementRecord e;
    e.id = id;
    e.type = type;
    e.nodes = std::move(nodes);
    m.elements[id] = e;
  };
  add(6, 1, {1, 2});
  add(7, 2, {1, 2, 5, 5});
  add(8, 3, {5});
  return m;
}

/// Transient with t = 0, 0.5, 1: node 2 UX = 0, 1.5e-3, -2.25; element 6 SAXL stored only
/// from t = 0.5 on (12345, -3); gap 1 force 0, 0, 4.5e6.
void write_transient(const std::string& path) {
  ResultsWriter w(path, small_model());
  w.begin_analysis(ResultsKind::Transient, "crash");
  const double ux[3] = {0.0, 1.5e-3, -2.25};
  const double saxl[3] = {kNaN, 12345.0, -3.0};
  const double gap[3] = {0.0, 0.0, 4.5e6};
  for (int k = 0; k < 3; ++k) {
    TimePoint p;
    p.time = 0.5 * k;
    p.displacement = Eigen::MatrixXd::Constant(3, 6, kNaN);
    p.displacement(1, 0) = ux[k];
    if (k > 0)
      p.element_results["spar"] = {{6}, {"SAXL"}, Eigen::MatrixXd::Constant(1, 1, saxl[k])};
    p.gap_forces = Eigen::VectorXd::Constant(1, gap[k]);
    w.append(p);
  }
  w.set_attribute("steps", 2.0);
  w.end_analysis();
}

TEST(PostParse, NsolEsolGapf) {
  auto n = parse_nsol(" 2 , ux ");
  EXPECT_EQ(n.kind, PostRequest::Nodal);
  EXPECT_EQ(n.id, 2);
  EXPECT_EQ(n.label, "UX");
  auto e = parse_esol("6,saxl");
  EXPECT_EQ(e.kind, PostRequest::Element);
  EXPECT_EQ(e.id, 6);
  EXPECT_EQ(e.label, "SAXL");
  auto g = parse_gapf("3");
  EXPECT_EQ(g.kind, PostRequest::Gap);
  EXPECT_EQ(g.id, 3);
  EXPECT_EQ(post_column_name(n), "N2_UX");
  EXPECT_EQ(post_column_name(e), "E6_SAXL");
  EXPECT_EQ(post_column_name(g), "GAP3");
  EXPECT_EQ(parse_nsol("10,MZ").label, "MZ");
}

template <typename F>
void expect_input_error(F f, const std::string& message) {
  try {
    f();
    ADD_FAILURE() << "expected InputError: " << message;
  } catch (const InputError& e) {
    EXPECT_EQ(std::string(e.what()), message);
  }
}

TEST(PostParse, Errors) {
  expect_input_error([] { parse_nsol("2"); }, "nodal request '2': expected NODE,LAB (e.g. 2,UX)");
  expect_input_error([] { parse_nsol("x,UX"); },
                     "nodal request 'x,UX': expected NODE,LAB (e.g. 2,UX)");
  expect_input_error([] { parse_nsol("0,UX"); },
                     "nodal request '0,UX': expected NODE,LAB (e.g. 2,UX)");
  expect_input_error([] { parse_nsol("2,UQ"); },
                     "nodal request '2,UQ': unknown label 'UQ' (expected UX UY UZ ROTX ROTY ROTZ, "
                     "VX VY VZ, AX AY AZ or FX FY FZ MX MY MZ)");
  expect_input_error([] { parse_esol("6"); },
                     "element request '6': expected ELEM,ITEM (e.g. 6,SAXL)");
  expect_input_error([] { parse_esol("6,"); },
                     "element request '6,': expected ELEM,ITEM (e.g. 6,SAXL)");
  expect_input_error([] { parse_gapf("1,2"); },
                     "gap request '1,2': expected the gap number NUM (e.g. 1)");
  expect_input_error([] { parse_gapf("-1"); },
                     "gap request '-1': expected the gap number NUM (e.g. 1)");
}

TEST_F(PostTest, CsvExactFormat) {
  write_transient(file("t.h5"));
  ResultsReader r(file("t.h5"));
  // Single column: every stored time, t = 0 included.
  EXPECT_EQ(post_csv(r, {parse_nsol("2,UX")}),
            "time,N2_UX\n"
            "0.0000000000e+00,0.0000000000e+00\n"
            "5.0000000000e-01,1.5000000000e-03\n"
            "1.0000000000e+00,-2.2500000000e+00\n");
  // Several columns: union of times, empty where a column has no value.
  EXPECT_EQ(post_csv(r, {parse_nsol("2,UX"), parse_esol("6,SAXL"), parse_gapf("1")}),
            "time,N2_UX,E6_SAXL,GAP1\n"
            "0.0000000000e+00,0.0000000000e+00,,0.0000000000e+00\n"
            "5.0000000000e-01,1.5000000000e-03,1.2345000000e+04,0.0000000000e+00\n"
            "1.0000000000e+00,-2.2500000000e+00,-3.0000000000e+00,4.5000000000e+06\n");
  EXPECT_EQ(post_csv(r, {parse_esol("6,SAXL")}),
            "time,E6_SAXL\n"
            "5.0000000000e-01,1.2345000000e+04\n"
            "1.0000000000e+00,-3.0000000000e+00\n");
  // A quantity stored at no time point (not written: OUTRES, or never computed) is an error,
  // not an empty column.
  try {
    post_csv(r, {parse_nsol("5,UY")});
    ADD_FAILURE() << "no error for a node without stored values";
  } catch (const InputError& e) {
    EXPECT_NE(std::string(e.what()).find("N5_UY: no value is stored"), std::string::npos)
        << e.what();
  }
  // Unknown entities are errors, not empty columns.
  EXPECT_THROW(post_csv(r, {parse_nsol("3,UX")}), InputError);
  EXPECT_THROW(post_csv(r, {parse_gapf("2")}), InputError);
}

TEST_F(PostTest, CsvMergesAnalysesOnUnionOfTimes) {
  {
    ResultsWriter w(file("m.h5"), small_model());
    w.begin_analysis(ResultsKind::ReducedTransient, "reduced");
    for (int k = 0; k < 3; ++k) {  // t = 0, 1, 2: node 1 UY master = 10 k
      TimePoint p;
      p.time = k;
      p.displacement = Eigen::MatrixXd::Constant(3, 6, kNaN);
      p.displacement(0, 1) = 10.0 * k;
      w.append(p);
    }
    w.begin_analysis(ResultsKind::Expansion, "expansion");
    TimePoint p;  // t = 1.5 (not a reduced time) and t = 2 (replaces the reduced value)
    p.displacement = Eigen::MatrixXd::Constant(3, 6, kNaN);
    for (double t : {1.5, 2.0}) {
      p.time = t;
      p.displacement(0, 1) = -t;
      p.displacement(2, 1) = 100.0 * t;
      w.append(p);
    }
  }
  ResultsReader r(file("m.h5"));
  EXPECT_EQ(post_csv(r, {parse_nsol("1,UY"), parse_nsol("5,UY")}),
            "time,N1_UY,N5_UY\n"
            "0.0000000000e+00,0.0000000000e+00,\n"
            "1.0000000000e+00,1.0000000000e+01,\n"
            "1.5000000000e+00,-1.5000000000e+00,1.5000000000e+02\n"
            "2.0000000000e+00,-2.0000000000e+00,2.0000000000e+02\n");
}

TEST_F(PostTest, FrequenciesModeShapeAndInfo) {
  {
    ResultsWriter w(file("modal.h5"), small_model());
    w.begin_analysis(ResultsKind::Modal, "modal");
    Eigen::MatrixXd s1 = Eigen::MatrixXd::Zero(3, 6), s2 = Eigen::MatrixXd::Zero(3, 6);
    s1(1, 0) = 1.0;
    s1(2, 1) = -0.5;
    s2(0, 5) = kNaN;  // absent DOF -> empty field
    w.write_modes({2.5, 1000.125}, {s1, s2});
    w.set_attribute("solver", "LANB");
    w.end_analysis();
  }
  ResultsReader r(file("modal.h5"));
  EXPECT_EQ(frequencies_csv(r),
            "mode,frequency_hz\n"
            "1,2.5000000000e+00\n"
            "2,1.0001250000e+03\n");
  const std::string z = "0.0000000000e+00";
  EXPECT_EQ(mode_shape_csv(r, 1),
            "node,UX,UY,UZ,ROTX,ROTY,ROTZ\n"
            "1," +
                z + "," + z + "," + z + "," + z + "," + z + "," + z + "\n" + "2,1.0000000000e+00," +
                z + "," + z + "," + z + "," + z + "," + z + "\n" + "5," + z +
                ",-5.0000000000e-01," + z + "," + z + "," + z + "," + z + "\n");
  EXPECT_NE(mode_shape_csv(r, 2).find("\n1," + z + "," + z + "," + z + "," + z + "," + z + ",\n"),
            std::string::npos);
  EXPECT_THROW(mode_shape_csv(r, 3), InputError);

  write_transient(file("t.h5"));
  const std::string info = results_info(ResultsReader(file("t.h5")));
  EXPECT_NE(info.find("Title: post test\n"), std::string::npos) << info;
  EXPECT_NE(info.find("Nodes: 3\nElements: 3\n"), std::string::npos) << info;
  EXPECT_NE(info.find("Analysis 1: transient (crash), status: complete\n"), std::string::npos)
      << info;
  EXPECT_NE(info.find("  time points: 3, time 0 .. 1\n"), std::string::npos) << info;
  EXPECT_NE(info.find("  element families: spar\n"), std::string::npos) << info;
  EXPECT_NE(info.find("  gap forces: 1\n"), std::string::npos) << info;
  EXPECT_NE(info.find("  steps = 2\n"), std::string::npos) << info;
  EXPECT_NE(results_info(r).find("  modes: 2\n  solver = LANB\n"), std::string::npos);
}

/// Minimal XML well-formedness check: declaration, balanced tags, quoted attributes.
/// Returns the root element name, or "" when malformed.
std::string check_xml(const std::string& text) {
  if (text.rfind("<?xml version=\"1.0\"?>\n", 0) != 0) return "";
  std::vector<std::string> stack;
  std::string root;
  std::size_t pos = text.find('\n') + 1;
  const std::regex attr_re(R"(^\s*([A-Za-z_][\w]*="[^"<>]*"\s*)*$)");
  while ((pos = text.find('<', pos)) != std::string::npos) {
    const std::size_t end = text.find('>', pos);
    if (end == std::string::npos) return "";
    std::string tag = text.substr(pos + 1, end - pos - 1);
    pos = end + 1;
    if (!tag.empty() && tag[0] == '/') {
      if (stack.empty() || stack.back() != tag.substr(1)) return "";
      stack.pop_back();
      continue;
    }
    const bool self_closing = !tag.empty() && tag.back() == '/';
    if (self_closing) tag.pop_back();
    const std::string name = tag.substr(0, tag.find(' '));
    const std::string attrs = tag.find(' ') == std::string::npos ? "" : tag.substr(tag.find(' '));
    if (name.empty() || !std::regex_match(attrs, attr_re)) return "";
    if (stack.empty()) {
      if (!root.empty()) return "";  // a second root element
      root = name;
    }
    if (!self_closing) stack.push_back(name);
  }
  return stack.empty() ? root : "";
}

std::string read_file(const fs::path& p) {
  std::ifstream f(p);
  std::stringstream ss;
  ss << f.rdbuf();
  return ss.str();
}

/// Whitespace-separated contents of the DataArray named `name`.
std::string data_array(const std::string& xml, const std::string& name) {
  const auto start = xml.find("Name=\"" + name + "\"");
  if (start == std::string::npos) return "<missing>";
  const auto open_end = xml.find('>', start) + 1;
  const auto close = xml.find("</DataArray>", open_end);
  std::istringstream in(xml.substr(open_end, close - open_end));
  std::string out, w;
  while (in >> w) out += (out.empty() ? "" : " ") + w;
  return out;
}

TEST_F(PostTest, VtuSeriesWellFormed) {
  // The arrays themselves are checked from Python (tests/export/check_export.py); here: one
  // binary .vtu per stored time point, a collection listing them, well-formed XML headers.
  write_transient(file("t.h5"));
  ResultsReader r(file("t.h5"));
  const fs::path out = dir_ / "vtk";
  const ExportSummary s = export_vtu_series(r, out.string(), "crash");
  EXPECT_EQ(s.frames, 3);
  EXPECT_EQ(s.points, 3u);
  EXPECT_EQ(s.cells, 3u);
  ASSERT_EQ(s.files.size(), 4u);
  EXPECT_EQ(fs::path(s.files.front()).filename(), "crash.pvd");
  const std::string pvd = read_file(out / "crash.pvd");
  EXPECT_EQ(check_xml(pvd), "VTKFile");
  EXPECT_NE(pvd.find("<DataSet timestep=\"0.5\" part=\"0\" file=\"crash_00001.vtu\"/>"),
            std::string::npos)
      << pvd;
  const std::string vtu = read_file(out / "crash_00002.vtu");
  const std::string header = vtu.substr(0, vtu.find("<AppendedData"));
  EXPECT_EQ(check_xml(header + "</VTKFile>"), "VTKFile");
  EXPECT_NE(header.find("compressor=\"vtkZLibDataCompressor\""), std::string::npos);
  EXPECT_NE(header.find("<Piece NumberOfPoints=\"3\" NumberOfCells=\"3\">"), std::string::npos);
  for (const char* name : {"U", "ROT", "V", "A", "RF", "RM", "element_id", "SAXL"})
    EXPECT_NE(header.find(std::string("Name=\"") + name + "\""), std::string::npos) << name;
}

}  // namespace
}  // namespace impactfe::test_post_csv
