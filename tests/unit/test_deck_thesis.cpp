// The thesis decks (tests/decks/thesis, cleaned from the OCR of Cho 1986, Appendices A-C) parse
// and build the models the spec describes (APDL_SUBSET §3 "Decoded" paragraphs).
#include <gtest/gtest.h>

#include <cmath>
#include <fstream>
#include <map>
#include <regex>
#include <sstream>

#include "deck/deck_reader.h"

namespace test_deck_thesis {

using namespace impactfe;

namespace {

std::string deck(const std::string& name) {
  return std::string(IMPACTFE_TEST_DECKS) + "/thesis/" + name;
}

double constraint(const LoadStep& s, int node, Dof d) {
  auto it = s.constraints.find(DofKey{node, d});
  return it == s.constraints.end() ? NAN : it->second;
}
bool constrained(const LoadStep& s, int node, Dof d) {
  return s.constraints.count(DofKey{node, d}) != 0;
}
double force(const LoadStep& s, int node, Dof d) {
  auto it = s.forces.find(DofKey{node, d});
  return it == s.forces.end() ? NAN : it->second;
}

}  // namespace

TEST(DeckThesis, AllDecksParse) {
  for (const char* name : {"pendulum1.inp", "pendulum2.inp", "crash1.inp", "crash2.inp",
                           "crash3.inp", "helmet_full.inp", "helmet_segen.inp", "helmet_use.inp"}) {
    SCOPED_TRACE(name);
    EXPECT_NO_THROW({
      Job job = read_deck(deck(name));
      EXPECT_EQ(job.model.dialect, Dialect::Classic4x);
    });
  }
}

TEST(DeckThesis, Pendulum1) {
  const Job job = read_deck(deck("pendulum1.inp"));
  const Model& m = job.model;
  EXPECT_EQ(m.title, "EXAMPLE #1. PENDULUM PROB.(CASE 1)");
  EXPECT_EQ(m.jobname, "pendulum1");
  ASSERT_EQ(m.nodes.size(), 2u);
  EXPECT_EQ(m.node(1).x, Vec3(0, 0, 0));
  EXPECT_DOUBLE_EQ(m.node(2).x.x(), -8.66025);
  EXPECT_DOUBLE_EQ(m.node(2).x.y(), -5.0);
  ASSERT_EQ(m.element_types.size(), 2u);
  EXPECT_EQ(m.element_type(1).ansys_name, "LINK8");
  EXPECT_EQ(m.element_type(2).ansys_name, "MASS21");
  EXPECT_EQ(m.element_type(2).key(3), 2);
  EXPECT_DOUBLE_EQ(m.real_sets.at(1).get(1), 0.1);  // LINK8 AREA
  EXPECT_DOUBLE_EQ(m.real_sets.at(2).get(1), 1.0);  // MASS21 mass
  EXPECT_DOUBLE_EQ(m.materials.at(1).get("EX", 0), 30e6);
  ASSERT_EQ(m.elements.size(), 2u);
  EXPECT_EQ(m.elements.at(1).nodes, (std::vector<int>{1, 2}));
  EXPECT_EQ(m.elements.at(1).type, 1);
  EXPECT_EQ(m.elements.at(2).nodes, (std::vector<int>{2}));
  EXPECT_EQ(m.elements.at(2).type, 2);
  EXPECT_EQ(m.elements.at(2).real, 2);
  ASSERT_EQ(job.steps.size(), 1u);
  const AnalysisRequest& a = *job.steps[0].analysis;
  EXPECT_EQ(a.options.type, AnalysisType::Transient);
  EXPECT_EQ(a.options.method, TransientMethod::Full);
  EXPECT_EQ(a.options.integrator, IntegratorKind::Houbolt);
  EXPECT_TRUE(a.options.large_deflection);
  EXPECT_FALSE(a.options.stress_stiffening);
  EXPECT_EQ(a.where.command, "/INPUT");
  ASSERT_EQ(a.load_steps.size(), 1u);
  const LoadStep& s = a.load_steps[0];
  EXPECT_DOUBLE_EQ(*s.time_end, 1.5);
  EXPECT_EQ(*s.n_substeps, 101);
  EXPECT_EQ(s.output.every, 1);
  EXPECT_TRUE(s.stepped);
  EXPECT_TRUE(s.time_integration);
  EXPECT_EQ(s.acel, Vec3(0, 386.4, 0));
  EXPECT_EQ(s.constraints.size(), 4u);  // UZ at 1, 2; UX, UY at 1
  EXPECT_EQ(constraint(s, 1, Dof::UZ), 0.0);
  EXPECT_EQ(constraint(s, 2, Dof::UZ), 0.0);
  EXPECT_EQ(constraint(s, 1, Dof::UX), 0.0);
  EXPECT_EQ(constraint(s, 1, Dof::UY), 0.0);
  EXPECT_TRUE(s.forces.empty());
  EXPECT_EQ(job.steps[0].model_snapshot->elements.size(), 2u);
}

TEST(DeckThesis, Pendulum2SpringWithoutMaterial) {
  const Job job = read_deck(deck("pendulum2.inp"));
  EXPECT_EQ(job.model.element_type(1).ansys_name, "COMBIN14");
  EXPECT_EQ(job.model.element_type(1).key(3), 2);
  EXPECT_DOUBLE_EQ(job.model.real_sets.at(1).get(1), 100.0);
  EXPECT_TRUE(job.model.materials.empty());  // springs and masses need no material
  ASSERT_EQ(job.steps.size(), 1u);
}

TEST(DeckThesis, Crash1) {
  const Job job = read_deck(deck("crash1.inp"));
  const Model& m = job.model;
  ASSERT_EQ(m.nodes.size(), 8u);
  const double x[] = {0, 2.5, 4.5, 6.25, 7.75, 9, 10};
  for (int i = 1; i <= 7; ++i) EXPECT_DOUBLE_EQ(m.node(i).x.x(), x[i - 1]);
  EXPECT_DOUBLE_EQ(m.node(10).x.x(), 15.0);
  EXPECT_EQ(m.element_type(1).ansys_name, "LINK1");
  ASSERT_EQ(m.elements.size(), 6u);  // E,1,2 + EGEN,6,1,1
  for (int e = 1; e <= 6; ++e) EXPECT_EQ(m.elements.at(e).nodes, (std::vector<int>{e, e + 1}));
  ASSERT_EQ(m.masters.size(), 7u);
  for (int i = 0; i < 7; ++i)
    EXPECT_EQ(m.masters[static_cast<std::size_t>(i)], (DofKey{i + 1, Dof::UX}));
  ASSERT_EQ(m.gap_conditions.size(), 1u);
  const GapCondition& g = m.gap_conditions[0];
  EXPECT_EQ(g.node_i, 10);
  EXPECT_EQ(g.node_j, 7);
  EXPECT_EQ(g.dof, Dof::UX);
  EXPECT_DOUBLE_EQ(g.stiffness, 1000.0);
  EXPECT_DOUBLE_EQ(g.gap, 0.1);
  EXPECT_EQ(g.where.line, 27);  // "GP,10,7,FX,1000,.1" is line 27 of crash1.inp

  ASSERT_EQ(job.steps.size(), 2u);
  const AnalysisRequest& a = *job.steps[0].analysis;
  EXPECT_EQ(a.options.type, AnalysisType::Transient);
  EXPECT_EQ(a.options.method, TransientMethod::Reduced);
  EXPECT_EQ(a.options.integrator, IntegratorKind::Houbolt);
  EXPECT_TRUE(a.options.lumped_mass);
  ASSERT_EQ(a.load_steps.size(), 3u);
  const double impulse[] = {-912.5, -1642.5, -1368.75, -1186.25, -1003.75, -821.25, -365};
  for (const auto& s : a.load_steps) {
    EXPECT_DOUBLE_EQ(*s.dt, 1e-4);
    EXPECT_TRUE(s.stepped);
    EXPECT_EQ(s.output.every, 1);  // ITER,1,1,1: write every step of the reduced run
  }
  EXPECT_FALSE(a.load_steps[0].time_end.has_value());
  EXPECT_DOUBLE_EQ(*a.load_steps[1].time_end, 1e-4);
  EXPECT_DOUBLE_EQ(*a.load_steps[2].time_end, 6e-3);
  for (int i = 1; i <= 7; ++i) {
    EXPECT_EQ(force(a.load_steps[0], i, Dof::UX), 0.0);  // F,1,FX,,,7 zeroes FX
    EXPECT_DOUBLE_EQ(force(a.load_steps[1], i, Dof::UX), impulse[i - 1]);
    EXPECT_EQ(force(a.load_steps[2], i, Dof::UX), 0.0);
  }
  EXPECT_EQ(a.load_steps[2].number, 3);
  EXPECT_EQ(a.load_steps[2].where.command, "LWRITE");

  ASSERT_TRUE(job.steps[1].expansion.has_value());
  const auto& req = job.steps[1].expansion->requests;
  ASSERT_EQ(req.size(), 2u);
  EXPECT_EQ(req[0].count, 1);
  EXPECT_DOUBLE_EQ(req[0].t_begin, 0.0);
  EXPECT_DOUBLE_EQ(req[0].t_end, 1e-4);
  EXPECT_EQ(req[1].count, 60);
  EXPECT_DOUBLE_EQ(req[1].t_begin, 1e-4);
  EXPECT_DOUBLE_EQ(req[1].t_end, 6e-3);
}

TEST(DeckThesis, CrashCasesGapsAndSteps) {
  const Job c2 = read_deck(deck("crash2.inp"));
  EXPECT_EQ(c2.model.element_type(1).key(1), 1);
  EXPECT_DOUBLE_EQ(c2.model.gap_conditions.at(0).stiffness, 10000.0);
  EXPECT_DOUBLE_EQ(c2.model.gap_conditions.at(0).gap, 0.04);
  EXPECT_DOUBLE_EQ(*c2.steps.at(0).analysis->load_steps.at(0).dt, 4e-5);
  const Job c3 = read_deck(deck("crash3.inp"));
  EXPECT_DOUBLE_EQ(c3.model.gap_conditions.at(0).stiffness, 100000.0);
  EXPECT_DOUBLE_EQ(c3.model.gap_conditions.at(0).gap, 0.01);
  EXPECT_DOUBLE_EQ(*c3.steps.at(0).analysis->load_steps.at(2).time_end, 6e-4);
  EXPECT_DOUBLE_EQ(force(c3.steps.at(0).analysis->load_steps.at(1), 2, Dof::UX), -16425.0);
}

namespace {

/// The decoded helmet mesh written independently in tests/decks/thesis/helmet_mesh.txt.
struct HelmetMesh {
  std::map<int, Vec3> nodes;
  std::map<int, std::vector<int>> shells;  // I, J, K
};

HelmetMesh read_helmet_mesh() {
  std::ifstream in(deck("helmet_mesh.txt"));
  std::stringstream ss;
  ss << in.rdbuf();
  const std::string text = ss.str();
  HelmetMesh mesh;
  const std::regex node_re(R"((\d+):\(([-0-9.]+),([-0-9.]+),([-0-9.]+)\))");
  for (std::sregex_iterator it(text.begin(), text.end(), node_re), end; it != end; ++it)
    mesh.nodes[std::stoi((*it)[1])] =
        Vec3(std::stod((*it)[2]), std::stod((*it)[3]), std::stod((*it)[4]));
  const std::size_t shell_part = text.find("Shell elements");
  const std::string shells = text.substr(text.find('\n', shell_part));
  const std::regex shell_re(R"((\d+):(\d+),(\d+),(\d+))");
  for (std::sregex_iterator it(shells.begin(), shells.end(), shell_re), end; it != end; ++it)
    mesh.shells[std::stoi((*it)[1])] = {std::stoi((*it)[2]), std::stoi((*it)[3]),
                                        std::stoi((*it)[4])};
  return mesh;
}

void expect_helmet_shells(const Model& m, const HelmetMesh& mesh) {
  ASSERT_EQ(mesh.shells.size(), 72u);
  for (const auto& [id, ijk] : mesh.shells) {
    SCOPED_TRACE("shell element " + std::to_string(id));
    ASSERT_EQ(m.elements.count(id), 1u);
    const ElementRecord& e = m.elements.at(id);
    EXPECT_EQ(m.element_type(e.type).ansys_name, "SHELL63");
    EXPECT_EQ(e.real, 1);
    EXPECT_EQ(e.mat, 1);
    // EN,id,I,J,K,K: triangle, K repeated as L.
    EXPECT_EQ(e.nodes, (std::vector<int>{ijk[0], ijk[1], ijk[2], ijk[2]}));
  }
}

void expect_helmet_shell_nodes(const Model& m, const HelmetMesh& mesh) {
  for (int id = 19; id <= 67; ++id) {
    SCOPED_TRACE("node " + std::to_string(id));
    ASSERT_EQ(m.nodes.count(id), 1u);
    EXPECT_NEAR((m.node(id).x - mesh.nodes.at(id)).norm(), 0.0, 1e-12);
    // Independent check: helmet nodes lie on z = (x^2 + y^2)/4 (APDL_SUBSET §3.7).
    const Vec3& x = m.node(id).x;
    EXPECT_NEAR(x.z(), (x.x() * x.x() + x.y() * x.y()) / 4.0, 1e-12);
  }
}

/// Head bricks and gap elements of helmet_full / helmet_use (APDL_SUBSET §3.10-§3.12 decoded).
void expect_head_and_gaps(const Model& m, int first_gap_id) {
  const std::map<int, std::vector<int>> bricks = {{73, {10, 13, 14, 11, 1, 4, 5, 2}},
                                                  {74, {11, 14, 15, 12, 2, 5, 6, 3}},
                                                  {75, {13, 16, 17, 14, 4, 7, 8, 5}},
                                                  {76, {14, 17, 18, 15, 5, 8, 9, 6}}};
  for (const auto& [id, nodes] : bricks) {
    SCOPED_TRACE("brick " + std::to_string(id));
    ASSERT_EQ(m.elements.count(id), 1u);
    EXPECT_EQ(m.elements.at(id).nodes, nodes);
    EXPECT_EQ(m.element_type(m.elements.at(id).type).ansys_name, "SOLID45");
    EXPECT_EQ(m.elements.at(id).mat, 2);
  }
  const std::vector<std::pair<int, int>> gaps = {{27, 10}, {31, 12}, {55, 16}, {59, 18}, {29, 11},
                                                 {41, 13}, {45, 15}, {57, 17}, {43, 14}, {68, 43}};
  for (std::size_t k = 0; k < gaps.size(); ++k) {
    const int id = first_gap_id + static_cast<int>(k);
    SCOPED_TRACE("gap " + std::to_string(id));
    ASSERT_EQ(m.elements.count(id), 1u);
    const ElementRecord& e = m.elements.at(id);
    EXPECT_EQ(m.element_type(e.type).ansys_name, "COMBIN40");
    EXPECT_EQ(e.nodes, (std::vector<int>{gaps[k].first, gaps[k].second}));
    EXPECT_EQ(e.real, k < 9 ? 2 : 3);
  }
  EXPECT_EQ(m.element_type(3).key(3), 3);
  EXPECT_EQ(m.element_type(3).key(6), 2);
  EXPECT_DOUBLE_EQ(m.real_sets.at(2).get(1), 1650.0);
  EXPECT_DOUBLE_EQ(m.real_sets.at(2).get(4), 0.1);
  EXPECT_DOUBLE_EQ(m.real_sets.at(3).get(4), 1.0);
}

void expect_helmet_steps(const AnalysisRequest& a) {
  ASSERT_EQ(a.load_steps.size(), 3u);
  const int nsub[] = {15, 25, 150};
  const double tend[] = {0.06, 0.07, 0.08};
  for (int k = 0; k < 3; ++k) {
    const LoadStep& s = a.load_steps[static_cast<std::size_t>(k)];
    EXPECT_EQ(s.number, k + 1);
    EXPECT_EQ(*s.n_substeps, nsub[k]);
    EXPECT_DOUBLE_EQ(*s.time_end, tend[k]);
    EXPECT_EQ(s.output.every, 1);
    EXPECT_EQ(s.acel, Vec3(0, 0, 386.4));
    EXPECT_TRUE(s.stepped);
    EXPECT_EQ(s.reformulation, 1);
    // D,68,ALL (6) + 5 DOFs at nodes 1-18 (90) + 5 DOFs at the 9 helmet master nodes (45).
    EXPECT_EQ(s.constraints.size(), 141u);
    EXPECT_TRUE(constrained(s, 68, Dof::ROTZ));
    EXPECT_TRUE(constrained(s, 18, Dof::ROTZ));
    EXPECT_FALSE(constrained(s, 18, Dof::UZ));
    EXPECT_TRUE(constrained(s, 29, Dof::UY));
    EXPECT_FALSE(constrained(s, 29, Dof::UZ));
    EXPECT_FALSE(constrained(s, 30, Dof::UX));
  }
  EXPECT_EQ(a.options.type, AnalysisType::Transient);
  EXPECT_EQ(a.options.integrator, IntegratorKind::Houbolt);
  EXPECT_TRUE(a.options.large_deflection);
  EXPECT_TRUE(a.options.stress_stiffening);
  EXPECT_FALSE(a.options.lumped_mass);
}

std::vector<DofKey> helmet_masters(bool with_head) {
  std::vector<DofKey> m;
  if (with_head)
    for (int n = 10; n <= 18; ++n) m.push_back({n, Dof::UZ});
  for (int n : {27, 29, 31, 41, 43, 45, 55, 57, 59}) m.push_back({n, Dof::UZ});
  return m;
}

}  // namespace

TEST(DeckThesis, HelmetFullMatchesDecodedMesh) {
  const HelmetMesh mesh = read_helmet_mesh();
  ASSERT_EQ(mesh.nodes.size(), 68u);
  const Job job = read_deck(deck("helmet_full.inp"));
  const Model& m = job.model;
  ASSERT_EQ(m.nodes.size(), 68u);
  for (const auto& [id, x] : mesh.nodes) {
    SCOPED_TRACE("node " + std::to_string(id));
    ASSERT_EQ(m.nodes.count(id), 1u);
    EXPECT_NEAR((m.node(id).x - x).norm(), 0.0, 1e-12);
  }
  expect_helmet_shell_nodes(m, mesh);
  expect_helmet_shells(m, mesh);
  EXPECT_EQ(m.elements.size(), 72u + 4u + 10u);
  expect_head_and_gaps(m, 77);
  EXPECT_DOUBLE_EQ(m.real_sets.at(1).get(1), 0.06);
  EXPECT_EQ(m.masters, helmet_masters(true));
  ASSERT_EQ(job.steps.size(), 1u);
  expect_helmet_steps(*job.steps[0].analysis);
  EXPECT_EQ(job.steps[0].model_snapshot->elements.size(), 86u);
}

TEST(DeckThesis, HelmetSuperelementGeneration) {
  const HelmetMesh mesh = read_helmet_mesh();
  const Job job = read_deck(deck("helmet_segen.inp"));
  const Model& m = job.model;
  expect_helmet_shell_nodes(m, mesh);
  expect_helmet_shells(m, mesh);
  EXPECT_EQ(m.nodes.size(), 49u);
  EXPECT_EQ(m.elements.size(), 72u);
  EXPECT_EQ(m.masters, helmet_masters(false));
  ASSERT_EQ(job.steps.size(), 1u);
  const AnalysisRequest& a = *job.steps[0].analysis;
  EXPECT_EQ(a.options.type, AnalysisType::Substructure);
  EXPECT_EQ(a.options.superelement_matrices, 2);  // KAY(6)=2 under KAN=7: K and M
  EXPECT_TRUE(a.options.stress_stiffening);
  EXPECT_FALSE(a.options.large_deflection);
  EXPECT_EQ(a.options.kay.at("7"), 1);
  ASSERT_EQ(a.load_steps.size(), 1u);
  EXPECT_EQ(a.load_steps[0].constraints.size(), 45u);
}

TEST(DeckThesis, HelmetUsePass) {
  const Job job = read_deck(deck("helmet_use.inp"));
  const Model& m = job.model;
  EXPECT_EQ(m.element_type(1).ansys_name, "MATRIX50");
  ASSERT_EQ(m.elements.count(1), 1u);
  EXPECT_EQ(m.elements.at(1).superelement_file, "unit:8");
  EXPECT_TRUE(m.elements.at(1).nodes.empty());
  EXPECT_EQ(m.elements.at(1).where.line, 44);  // "E,1,8"
  EXPECT_EQ(m.elements.size(), 1u + 4u + 10u);
  expect_head_and_gaps(m, 77);
  EXPECT_EQ(m.nodes.size(), 18u + 9u + 1u);
  EXPECT_EQ(m.masters, helmet_masters(true));
  ASSERT_EQ(job.steps.size(), 1u);
  expect_helmet_steps(*job.steps[0].analysis);
}

}  // namespace test_deck_thesis
