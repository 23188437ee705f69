// `impactfe report` on a contact model: a shell plate with CONTA174 faces over a rigid TARGE170
// floor larger than the plate. The floor is a see-through overlay that does not set the view's
// extent, the contact faces are not drawn over the shell, the parts are named by the shell and
// not by its contact faces, the contact pair's total force is ΣFN of its elements, and /UNITS
// labels the axes.
#include <gtest/gtest.h>
#include <unistd.h>

#include <cmath>
#include <filesystem>
#include <limits>
#include <nlohmann/json.hpp>

#include "results/report.h"
#include "results/report_units.h"
#include "results/results_file.h"

namespace impactfe::test_report_contact {
namespace {

namespace fs = std::filesystem;
using json = nlohmann::json;
constexpr double kNaN = std::numeric_limits<double>::quiet_NaN();

/// Nodes 1-4: a unit shell square at z = 0.1; nodes 5-8: a 10 x 10 floor at z = 0; node 9: the
/// floor's pilot. Element 1: SHELL181; 2: CONTA174 on the shell's nodes (real 3); 3: TARGE170
/// floor (real 3); 4: the pilot (TARGE170).
Model plate_on_floor(const std::string& units) {
  Model m;
  m.units = units;
  const double xyz[9][3] = {{0, 0, 0.1}, {1, 0, 0.1}, {1, 1, 0.1}, {0, 1, 0.1}, {-5, -5, 0},
                            {5, -5, 0},  {5, 5, 0},   {-5, 5, 0},  {0, 0, -1}};
  for (int id = 1; id <= 9; ++id) {
    Node n;
    n.id = id;
    n.x = Vec3(xyz[id - 1][0], xyz[id - 1][1], xyz[id - 1][2]);
    m.nodes[id] = n;
  }
  const char* names[] = {"SHELL181", "CONTA174", "TARGE170"};
  for (int t = 1; t <= 3; ++t) {
    ElementType et;
    et.id = t;
    et.ansys_name = names[t - 1];
    m.element_types[t] = et;
  }
  auto add = [&](int id, int type, int real, std::vector<int> nodes) {
    ElementRecord e;
    e.id = id;
    e.type = type;
    e.real = real;
    e.nodes = std::move(nodes);
    m.elements[id] = e;
  };
  add(1, 1, 1, {1, 2, 3, 4});
  add(2, 2, 3, {1, 2, 3, 4});
  add(3, 3, 3, {5, 6, 7, 8});
  add(4, 3, 3, {9});
  return m;
}

json report_of(const fs::path& dir, const std::string& units) {
  const std::string path = (dir / (units.empty() ? "plain.h5" : "units.h5")).string();
  {
    ResultsWriter w(path, plate_on_floor(units));
    w.begin_analysis(ResultsKind::Transient, "drop");
    for (int k = 0; k < 20; ++k) {
      TimePoint p;
      p.time = 1e-4 * k;
      p.displacement = Eigen::MatrixXd::Constant(9, 6, kNaN);
      p.velocity = p.acceleration = p.reaction = p.displacement;
      for (int i = 0; i < 9; ++i)
        for (int d = 0; d < 3; ++d) p.displacement(i, d) = i < 4 && d == 2 ? -1e-3 * k : 0.0;
      // The contact element carries FN = 100 k from step 10 on, FT = 10 k.
      Eigen::MatrixXd contact = Eigen::MatrixXd::Zero(1, 6);
      if (k >= 10) contact.row(0) << 1.0, 100.0 * k, 1e-6, 0.0, 10.0 * k, 0.0;
      p.element_results["contact"] = {{2}, {"STAT", "FN", "PENE", "GAP", "FT", "SLIDE"}, contact};
      Eigen::MatrixXd shell(1, 1);
      shell << 1e6 * k;
      p.element_results["shell"] = {{1}, {"SEQV_TOP"}, shell};
      p.energy = {{"kinetic", 1.0}, {"strain", 0.0}, {"external_work", 1.0}};
      w.append(p);
    }
    w.end_analysis();
  }
  return json::parse(report_data_json(ResultsReader(path), {}));
}

class ReportContactTest : public ::testing::Test {
 protected:
  void SetUp() override {
    dir_ = fs::temp_directory_path() / ("impactfe_report_contact_" + std::to_string(getpid()));
    fs::remove_all(dir_);
    fs::create_directories(dir_);
  }
  void TearDown() override { fs::remove_all(dir_); }
  fs::path dir_;
};

TEST_F(ReportContactTest, FloorIsAnOverlayAndContactFacesAreNotDrawn) {
  const json d = report_of(dir_, "");
  const auto& mesh = d["mesh"];
  // The shell quad alone in the structure's triangles (the CONTA174 face on it is not drawn).
  EXPECT_EQ(mesh["triangles"].size(), 6u);
  for (int e : mesh["triangle_element"]) EXPECT_EQ(mesh["element_ids"][e], 1);
  // The floor: one quad as two see-through triangles; the pilot is not drawn.
  EXPECT_EQ(mesh["overlay_triangles"].size(), 6u);
  for (int e : mesh["overlay_element"]) EXPECT_EQ(mesh["element_ids"][e], 3);
  // The view's extent is the shell's four nodes, not the 10 x 10 floor.
  EXPECT_EQ(mesh["framed_nodes"], json::array({0, 1, 2, 3}));
  // Parts: the shell (not its contact faces) and the rigid floor.
  ASSERT_EQ(mesh["bodies"].size(), 3u);
  EXPECT_EQ(mesh["bodies"][0]["name"], "the SHELL181 type 1 mat 1 real 1 part");
  EXPECT_EQ(mesh["bodies"][1]["name"], "the rigid target (TARGE170)");
  EXPECT_EQ(mesh["bodies"][2]["name"], "node 9");
  // No gap rows for the contact element: it is summed per pair instead.
  EXPECT_TRUE(d["gap_status"]["rows"].empty());
}

TEST_F(ReportContactTest, PairForceIsTheSumOfItsContactElements) {
  const json d = report_of(dir_, "");
  ASSERT_EQ(d["contact_force"].size(), 1u);
  const json& f = d["contact_force"][0];
  EXPECT_EQ(f["title"], "Contact force of pair 3 (1 contact elements) vs time");
  ASSERT_EQ(f["series"].size(), 2u);
  EXPECT_EQ(f["series"][0]["label"], "normal ΣFN");
  EXPECT_DOUBLE_EQ(f["series"][0]["peak_abs"].get<double>(), 1900.0);
  EXPECT_DOUBLE_EQ(f["series"][1]["peak_abs"].get<double>(), 190.0);
  EXPECT_NEAR(d["first_contact_time"].get<double>(), 1e-3, 1e-15);
  EXPECT_EQ(f["ylabel"], "Contact force");  // no /UNITS: no unit
  EXPECT_TRUE(d["units"].is_null());
}

TEST_F(ReportContactTest, UnitsLabelTheAxes) {
  const json d = report_of(dir_, "MPA");
  EXPECT_EQ(d["units"]["stress"], "MPa");
  EXPECT_EQ(d["units"]["energy"], "mJ");
  EXPECT_EQ(d["contact_force"][0]["xlabel"], "Time (s)");
  EXPECT_EQ(d["contact_force"][0]["ylabel"], "Contact force (N)");
  bool stress = false, displacement = false;
  for (const auto& f : d["figures"]) {
    const std::string y = f["ylabel"];
    if (y.rfind("Stress", 0) == 0) stress = y.find("(MPa)") != std::string::npos;
    if (y.rfind("Displacement", 0) == 0) displacement = y.find("(mm)") != std::string::npos;
  }
  EXPECT_TRUE(stress);
  EXPECT_TRUE(displacement);
}

TEST_F(ReportContactTest, InitialKineticEnergyIsPutInLikeExternalWork) {
  // A plate dropped with an initial velocity (IC): T0 = 5 at the initial state (load step 0), no
  // external work; later T = 3, U = 1.5: the integrator removed T0 − (T + U) = 0.5, not −4.5.
  // A second analysis continues the run from a restart point (no initial state of its own): it
  // carries the run's T0.
  const std::string path = (dir_ / "dropped.h5").string();
  {
    ResultsWriter w(path, plate_on_floor(""));
    for (int analysis = 0; analysis < 2; ++analysis) {
      w.begin_analysis(ResultsKind::Transient, "drop");
      for (int k = 0; k < 4; ++k) {
        TimePoint p;
        p.time = 1e-4 * (4 * analysis + k);
        p.load_step = analysis == 0 && k == 0 ? 0 : 1;
        p.substep = 4 * analysis + k;
        p.displacement = Eigen::MatrixXd::Zero(9, 6);
        p.velocity = p.acceleration = p.reaction = p.displacement;
        const bool start = analysis == 0 && k == 0;
        p.energy = {{"kinetic", start           ? 5.0
                                : analysis == 0 ? 3.0
                                                : 2.0},
                    {"strain", start           ? 0.0
                               : analysis == 0 ? 1.5
                                               : 2.5},
                    {"external_work", 0.0}};
        w.append(p);
      }
      w.end_analysis();
    }
  }
  const json d = json::parse(report_data_json(ResultsReader(path), {}));
  ASSERT_EQ(d["energy"].size(), 2u);
  for (const json& e : d["energy"]) {
    EXPECT_NEAR(e["final"]["numerical_dissipation"].get<double>(), 0.5, 1e-12) << e["analysis"];
    EXPECT_NEAR(e["final"]["initial_kinetic"].get<double>(), 5.0, 1e-12) << e["analysis"];
  }
  // The remainder starts at 0 (the initial state balances).
  for (const json& c : d["energy"][0]["curves"])
    if (c["label"] == "numerical_dissipation") EXPECT_NEAR(c["peak_abs"].get<double>(), 0.5, 1e-6);
  // Without an initial velocity nothing is added (and no T0 row).
  EXPECT_FALSE(report_of(dir_, "")["energy"][0]["final"].contains("initial_kinetic"));
}

TEST(ReportUnits, SystemsAndQuantities) {
  EXPECT_FALSE(unit_labels("USER"));
  EXPECT_FALSE(unit_labels(""));
  const auto bin = unit_labels("bin");
  ASSERT_TRUE(bin);
  EXPECT_EQ(unit_of_quantity(*bin, "Stress SEQV"), "psi");
  EXPECT_EQ(unit_of_quantity(*bin, "Acceleration AZ"), "in/s²");
  EXPECT_EQ(unit_of_quantity(*bin, "FORC"), "lbf");
  EXPECT_EQ(unit_of_quantity(*bin, "STAT"), "");
  EXPECT_EQ(unit_of_quantity(*bin, "EPEQ"), "");
}

}  // namespace
}  // namespace impactfe::test_report_contact
