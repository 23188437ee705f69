// `impactfe report`: min/max sampling, the automatic choice of nodes and elements, gap status,
// energy remainder and frames, on a small hand-built results file whose answers are known.
#include <gtest/gtest.h>
#include <unistd.h>

#include <cmath>
#include <cstdio>
#include <cstring>
#include <filesystem>
#include <limits>
#include <nlohmann/json.hpp>
#include <regex>

#include "core/errors.h"
#include "results/report.h"
#include "results/results_file.h"

namespace impactfe::test_report {
namespace {

namespace fs = std::filesystem;
using json = nlohmann::json;
constexpr double kNaN = std::numeric_limits<double>::quiet_NaN();
constexpr double kPi = 3.14159265358979323846;

TEST(ReportSampling, ShortSeriesUnchanged) {
  std::vector<std::pair<double, double>> s = {{0, 1}, {1, 2}, {2, -1}};
  EXPECT_EQ(sample_min_max(s, 4), s);
}

TEST(ReportSampling, LongSeriesKeepsPeaksEndsAndOrder) {
  // 100 001 points of a sine with one narrow spike each way: a plain stride would miss them.
  std::vector<std::pair<double, double>> s;
  for (int i = 0; i <= 100000; ++i) s.emplace_back(i * 1e-4, std::sin(i * 1e-3));
  s[31234].second = 7.5;
  s[77777].second = -9.25;
  const auto out = sample_min_max(s, 2000);
  EXPECT_LE(out.size(), 2000u);
  EXPECT_GE(out.size(), 1900u);
  EXPECT_EQ(out.front(), s.front());
  EXPECT_EQ(out.back(), s.back());
  double hi = -1e300, lo = 1e300;
  for (std::size_t k = 0; k < out.size(); ++k) {
    hi = std::max(hi, out[k].second);
    lo = std::min(lo, out[k].second);
    if (k > 0) EXPECT_LT(out[k - 1].first, out[k].first);
  }
  EXPECT_EQ(hi, 7.5);
  EXPECT_EQ(lo, -9.25);
  EXPECT_THROW(sample_min_max(s, 3), InputError);
}

/// Nodes 1-2-3 (LINK8 10, 11) and 4-5 (LINK8 12) joined by gap 20 (3-4); gap 21 ties node 5 to
/// the fixed node 6. UX amplitudes 1, 3, 2 | 0.5, 0.8 | 0; UY 1 % of UX. SAXL peaks 100, 500,
/// 50. Gap 20 closes at t = 0.5 (FORC -10), gap 21 stays open. 100 points, t = 0 .. 0.99.
Model two_part_model() {
  Model m;
  m.title = "report test <two parts>";
  for (int id = 1; id <= 6; ++id) {
    Node n;
    n.id = id;
    n.x = Vec3(double(id), 0.0, 0.0);
    m.nodes[id] = n;
  }
  const char* names[] = {"LINK8", "COMBIN40"};
  for (int t = 1; t <= 2; ++t) {
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
  add(10, 1, {1, 2});
  add(11, 1, {2, 3});
  add(12, 1, {4, 5});
  add(20, 2, {3, 4});
  add(21, 2, {5, 6});
  return m;
}

class ReportTest : public ::testing::Test {
 protected:
  void SetUp() override {
    const auto* info = ::testing::UnitTest::GetInstance()->current_test_info();
    dir_ = fs::temp_directory_path() /
           (std::string("impactfe_report_") + info->name() + "_" + std::to_string(getpid()));
    fs::remove_all(dir_);
    fs::create_directories(dir_);
    path_ = (dir_ / "two.h5").string();
    ResultsWriter w(path_, two_part_model());
    w.begin_analysis(ResultsKind::Transient, "drop");
    const double amp[6] = {1.0, 3.0, 2.0, 0.5, 0.8, 0.0};
    for (int k = 0; k < 100; ++k) {
      TimePoint p;
      p.time = 0.01 * k;
      const double s = std::sin(2 * kPi * p.time);
      p.displacement = Eigen::MatrixXd::Constant(6, 6, kNaN);
      p.velocity = p.acceleration = p.reaction = p.displacement;
      for (int i = 0; i < 6; ++i) {
        p.displacement(i, 0) = amp[i] * s;
        p.displacement(i, 1) = 0.01 * amp[i] * s;
        p.displacement(i, 2) = 0.0;
      }
      Eigen::MatrixXd saxl(3, 1);
      saxl << 100 * s, 500 * s, 50 * s;
      p.element_results["spar"] = {{10, 11, 12}, {"SAXL"}, saxl};
      const bool closed = p.time >= 0.5 - 1e-12;
      Eigen::MatrixXd gap(2, 2);
      gap << (closed ? -10.0 : 0.0), (closed ? 1.0 : 0.0), 0.0, 0.0;
      p.element_results["gap"] = {{20, 21}, {"FORC", "STAT"}, gap};
      p.energy = {{"kinetic", 1.0},
                  {"strain", 2.0},
                  {"external_work", 10.0 * p.time},
                  {"gap_work", 0.5},
                  {"dissipation", 0.25}};
      w.append(p);
    }
    w.end_analysis();
  }
  void TearDown() override {
    if (!std::getenv("IMPACTFE_KEEP_TEST_FILES")) fs::remove_all(dir_);
  }
  json data(const ReportOptions& options = {}) const {
    return json::parse(report_data_json(ResultsReader(path_), options));
  }
  static std::vector<std::string> labels(const json& figure) {
    std::vector<std::string> out;
    for (const auto& s : figure["series"]) out.push_back(s["label"].get<std::string>());
    return out;
  }
  fs::path dir_;
  std::string path_;
};

TEST_F(ReportTest, AutomaticChoicePerPart) {
  const json d = data();
  EXPECT_EQ(d["directions"], json::array({"X"}));  // UY is 1 % of UX: below 10 %
  const auto& figs = d["figures"];
  ASSERT_EQ(figs.size(), 3u);  // U of each part (V and A are not stored), stress
  // Part 1: the largest response (node 2) and its moving gap node (3); part 2: nodes 4, 5.
  EXPECT_EQ(figs[0]["title"], "Displacement UX of the LINK8 type 1 mat 1 real 1 part 1 vs time");
  EXPECT_EQ(labels(figs[0]), (std::vector<std::string>{"Node 2 UX", "Node 3 UX"}));
  EXPECT_EQ(labels(figs[1]), (std::vector<std::string>{"Node 4 UX", "Node 5 UX"}));
  EXPECT_NEAR(figs[0]["series"][0]["peak_abs"].get<double>(), 3.0, 1e-12);
  EXPECT_EQ(figs[0]["series"][0]["n"], 100);
  // The most stressed LINK8 is element 11.
  EXPECT_EQ(figs[2]["title"], "Stress of element 11 (LINK8) vs time");
  EXPECT_EQ(figs[2]["ylabel"], "Stress SAXL");
  EXPECT_EQ(labels(figs[2]), (std::vector<std::string>{"Element 11 (LINK8) SAXL"}));
  EXPECT_NEAR(figs[2]["series"][0]["peak_abs"].get<double>(), 500.0, 1e-9);
  EXPECT_EQ(d["mesh"]["bodies"].size(), 3u);  // two parts and the node held by a gap only
}

TEST_F(ReportTest, GapsEnergyAndFrames) {
  ReportOptions options;
  options.max_frames = 10;
  const json d = data(options);
  const auto& rows = d["gap_status"]["rows"];
  ASSERT_EQ(rows.size(), 2u);
  EXPECT_EQ(rows[0]["label"], "Element 20 (COMBIN40)");
  EXPECT_EQ(rows[0]["changes"], json::parse("[[0.0, 0.0], [0.5, 1.0]]"));
  EXPECT_EQ(rows[1]["changes"], json::parse("[[0.0, 0.0]]"));
  ASSERT_EQ(d["gap_force"]["series"].size(), 2u);
  EXPECT_EQ(d["gap_force"]["series"][0]["label"], "Element 20 (COMBIN40) FORC");
  // Remainder at the end: W - (T + U + Wg + D) = 9.9 - 3.75.
  ASSERT_EQ(d["energy"].size(), 1u);
  EXPECT_NEAR(d["energy"][0]["final"]["numerical_dissipation"].get<double>(), 6.15, 1e-12);
  const auto& times = d["frames"]["times"];
  ASSERT_EQ(times.size(), 10u);
  EXPECT_DOUBLE_EQ(times[0].get<double>(), 0.0);
  EXPECT_DOUBLE_EQ(times[9].get<double>(), 0.99);
  // 10 frames x 6 nodes x 3 float32 values, base64.
  EXPECT_EQ(d["frames"]["U"].get<std::string>().size(), (10 * 6 * 3 * 4 + 2) / 3 * 4);
  // Element fields: SAXL, FORC (gaps), STAT; one value per element and frame.
  std::vector<std::string> names;
  for (const auto& f : d["frames"]["fields"]) names.push_back(f["name"]);
  EXPECT_EQ(names, (std::vector<std::string>{"SAXL", "FORC", "STAT"}));
  // The lines of the 3-D view: three spars and two gaps.
  EXPECT_EQ(d["mesh"]["lines"].size(), 10u);
}

TEST_F(ReportTest, ChosenNodesItemsAndErrors) {
  ReportOptions options;
  options.nodes = {1};
  options.elements = {12};
  options.items = {"uy", "SAXL"};
  const json d = data(options);
  ASSERT_EQ(d["figures"].size(), 2u);
  EXPECT_EQ(d["figures"][0]["title"], "Displacement UY of node 1 vs time");
  EXPECT_EQ(labels(d["figures"][1]), (std::vector<std::string>{"Element 12 (LINK8) SAXL"}));
  EXPECT_FALSE(d["selection"]["nodes_auto"].get<bool>());

  options = {};
  options.nodes = {99};
  EXPECT_THROW(data(options), InputError);
  options = {};
  options.elements = {12};
  options.items = {"SEQV"};  // not stored for a spar: the reader names what is
  try {
    data(options);
    ADD_FAILURE() << "expected InputError";
  } catch (const InputError& e) {
    EXPECT_NE(std::string(e.what()).find("available: SAXL"), std::string::npos) << e.what();
  }
}

TEST_F(ReportTest, PageIsSelfContained) {
  const std::string html = report_html(ResultsReader(path_), {});
  EXPECT_EQ(html.rfind("<!DOCTYPE html>", 0), 0u);
  EXPECT_EQ(html.find("<!--IMPACTFE:"), std::string::npos);
  // No external script, style sheet or image.
  EXPECT_FALSE(std::regex_search(
      html, std::regex(R"((src|href)\s*=\s*["']?\s*(https?:)?//)", std::regex::icase)));
  // The title is escaped in the HTML and "<" never appears raw inside the JSON data.
  EXPECT_NE(html.find("report test &lt;two parts&gt;"), std::string::npos);
  const auto begin = html.find("id=\"impactfe-data\">");
  const auto end = html.find("</script>", begin);
  ASSERT_NE(begin, std::string::npos);
  const std::string data = html.substr(begin + 19, end - begin - 19);
  EXPECT_EQ(data.find('<'), std::string::npos);
  EXPECT_EQ(json::parse(data)["title"], "report test <two parts>");

  const auto bytes = write_report(ResultsReader(path_), {}, (dir_ / "r.html").string());
  EXPECT_EQ(bytes, fs::file_size(dir_ / "r.html"));
  EXPECT_THROW(write_report(ResultsReader(path_), {}, (dir_ / "no" / "r.html").string()),
               InputError);
}

TEST(ReportTitle, BytesThatAreNotUtf8AreReplaced) {
  const fs::path dir =
      fs::temp_directory_path() / ("impactfe_report_title_" + std::to_string(getpid()));
  fs::remove_all(dir);
  fs::create_directories(dir);
  Model m = two_part_model();
  m.title = "CASE \xb0 1";  // Latin-1 degree sign from an old deck
  const std::string path = (dir / "t.h5").string();
  {
    ResultsWriter w(path, m);
    w.begin_analysis(ResultsKind::Static, "static");
    w.end_analysis();
  }
  const json d = json::parse(report_data_json(ResultsReader(path), {}));
  EXPECT_EQ(d["title"], "CASE \xef\xbf\xbd 1");  // U+FFFD
  fs::remove_all(dir);
}

/// Base64 float32 of the page data back to numbers.
std::vector<float> decode_floats(const std::string& b64) {
  const std::string alphabet = "ABCDEFGHIJKLMNOPQRSTUVWXYZabcdefghijklmnopqrstuvwxyz0123456789+/";
  std::vector<unsigned char> bytes;
  std::uint32_t acc = 0;
  int bits = 0;
  for (char c : b64) {
    if (c == '=') break;
    acc = (acc << 6) | static_cast<std::uint32_t>(alphabet.find(c));
    bits += 6;
    if (bits >= 8) {
      bits -= 8;
      bytes.push_back(static_cast<unsigned char>((acc >> bits) & 0xff));
    }
  }
  std::vector<float> out(bytes.size() / 4);
  std::memcpy(out.data(), bytes.data(), out.size() * 4);
  return out;
}

/// A long history like the one in issue 10: 190 nodes (a 19 x 10 shell grid), 3000 stored
/// points with a narrow peak at step 1234. The page stays small: curves sampled to at most
/// 2000 points with the peak kept, at most 300 frames.
TEST(ReportLongHistory, SampledAndSmall) {
  const fs::path dir =
      fs::temp_directory_path() / ("impactfe_report_long_" + std::to_string(getpid()));
  fs::remove_all(dir);
  fs::create_directories(dir);
  Model m;
  m.title = "long history";
  for (int j = 0; j < 10; ++j)
    for (int i = 0; i < 19; ++i) {
      Node n;
      n.id = 1 + i + 19 * j;
      n.x = Vec3(i, j, 0.0);
      m.nodes[n.id] = n;
    }
  ElementType shell;
  shell.id = 1;
  shell.ansys_name = "SHELL63";
  m.element_types[1] = shell;
  std::vector<int> ids;
  for (int j = 0; j < 9; ++j)
    for (int i = 0; i < 18; ++i) {
      ElementRecord e;
      e.id = 1 + i + 18 * j;
      e.type = 1;
      const int a = 1 + i + 19 * j;
      e.nodes = {a, a + 1, a + 20, a + 19};
      m.elements[e.id] = e;
      ids.push_back(e.id);
    }
  const std::string path = (dir / "long.h5").string();
  {
    ResultsWriter w(path, m);
    w.begin_analysis(ResultsKind::Transient, "long");
    for (int k = 0; k < 3000; ++k) {
      TimePoint p;
      p.time = 1e-4 * k;
      const double s = std::sin(0.01 * k) + (k == 1234 ? 5.0 : 0.0);
      p.displacement = Eigen::MatrixXd::Zero(190, 6);
      for (int i = 0; i < 190; ++i) p.displacement(i, 2) = s * (1.0 + 0.01 * i);
      p.velocity = p.acceleration = p.displacement;
      p.reaction = Eigen::MatrixXd::Constant(190, 6, kNaN);
      Eigen::MatrixXd seqv(162, 2);
      for (int e = 0; e < 162; ++e) seqv.row(e) << std::abs(s) * (1 + e), std::abs(s);
      p.element_results["shell"] = {ids, {"SEQV_TOP", "SEQV_BOT"}, seqv};
      w.append(p);
    }
    w.end_analysis();
  }
  const std::string html = report_html(ResultsReader(path), {});
  std::printf("long-history page: %zu bytes\n", html.size());
  EXPECT_LT(html.size(), 4'000'000u);
  const auto begin = html.find("id=\"impactfe-data\">") + 19;
  const json d = json::parse(html.substr(begin, html.find("</script>", begin) - begin));
  ASSERT_FALSE(d["figures"].empty());
  for (const auto& f : d["figures"])
    for (const auto& c : f["series"]) {
      EXPECT_EQ(c["n_stored"], 3000);
      EXPECT_LE(c["n"].get<int>(), 2000);
      const auto y = decode_floats(c["y"]);
      ASSERT_EQ(y.size(), c["n"].get<std::size_t>());
      float peak = 0;
      for (float v : y) peak = std::max(peak, std::abs(v));
      EXPECT_FLOAT_EQ(peak, static_cast<float>(c["peak_abs"].get<double>())) << c["label"];
    }
  EXPECT_EQ(d["frames"]["times"].size(), 300u);
  EXPECT_DOUBLE_EQ(d["frames"]["times"].back().get<double>(), 0.2999);
  if (!std::getenv("IMPACTFE_KEEP_TEST_FILES")) fs::remove_all(dir);
}

}  // namespace
}  // namespace impactfe::test_report
