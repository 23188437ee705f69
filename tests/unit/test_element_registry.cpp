// The element registry (src/elements/element_registry.h). The first part is the demonstration
// the architecture asks for: a complete new element type — class, factory and ONE registration
// line — defined in this file only, then used by a deck through the unchanged reader, solver,
// results file and VTK cell table. The second part checks the built-in registrations against
// their element classes.
#include <gtest/gtest.h>
#include <algorithm>

#include <fmt/format.h>

#include <Eigen/Geometry>

#include <fstream>
#include <map>

#include "../support/run_deck.h"
#include "elements/cell_topology.h"
#include "elements/element_fields.h"
#include "elements/element_registry.h"
#include "elements/line_element_data.h"
#include "results/report_mesh.h"
#include "results/vtk_frames.h"

namespace impactfe::test_element_registry {
namespace {

// ---- a test-only element: a 2-node axial spring along X with stiffness R1 ------------------

class AxialTestSpring final : public Element {
 public:
  AxialTestSpring(int id, int node_i, int node_j, double k)
      : Element(id), dofs_{{node_i, Dof::UX}, {node_j, Dof::UX}}, k_(k) {}
  const char* family() const override { return "AxialTestSpring"; }
  const std::vector<DofKey>& dofs() const override { return dofs_; }
  bool is_nonlinear(const ElementContext&) const override { return false; }
  void tangent(const ElementContext&, const Eigen::VectorXd& u, Eigen::MatrixXd& K,
               Eigen::VectorXd& f) const override {
    K.resize(2, 2);
    K << k_, -k_, -k_, k_;
    f = K * u;
  }
  void mass(const ElementContext&, Eigen::MatrixXd& M) const override { M.setZero(2, 2); }
  const std::vector<std::string>& result_names() const override { return names(); }
  void results(const ElementContext&, const Eigen::VectorXd& u, const Eigen::VectorXd&,
               ElementResultValues& out) const override {
    out = {k_ * (u(1) - u(0))};
  }
  static const std::vector<std::string>& names() {
    static const std::vector<std::string> n = {"FORC"};
    return n;
  }

 private:
  std::vector<DofKey> dofs_;
  double k_;
};

std::unique_ptr<Element> make_axial_test_spring(const ElementBuildContext& ctx,
                                                const ElementRecord& record) {
  const auto [ni, nj] = line_data::distinct_node_pair(ctx.model, record, "AxialTestSpring");
  const double k = line_data::real_set(ctx.model, record, "AxialTestSpring").get(1);
  return std::make_unique<AxialTestSpring>(record.id, ni.id, nj.id, k);
}

// The one registration line (its cell and shape role tell the mesher, the VTK export, the POST1
// pictures and the report what it is).
// clang-format off
const ElementRegistration kTestSpring{{.name = "TSPRING", .number = 9901, .family = "AxialTestSpring", .n_nodes = 2, .real_constants = RealConstantUse::Required, .vtk_cell = VtkCell::Line, .role = ShapeRole::Line, .result_names = AxialTestSpring::names(), .create = make_axial_test_spring}};
// The same class registered as a gap between two bodies: one more line, nothing else.
const ElementRegistration kTestGap{{.name = "TGAP", .number = 9902, .family = "AxialTestSpring", .n_nodes = 2, .real_constants = RealConstantUse::Required, .vtk_cell = VtkCell::Line, .role = ShapeRole::Gap, .result_names = AxialTestSpring::names(), .create = make_axial_test_spring}};
// clang-format on

TEST(ElementRegistry, ATestOnlyElementRunsThroughTheWholeProgram) {
  // Two TSPRINGs in series (k = 100, 300), node 1 fixed, F = 30 at node 3:
  // u2 = 30/100 = 0.3, u3 = 0.3 + 30/300 = 0.4; the deck names the type by name and by number.
  const auto dir = testing::fresh_directory("element_registry");
  const std::string deck = (dir / "tspring.inp").string();
  {
    std::ofstream f(deck);
    f << "/PREP7\nET,1,TSPRING\nET,2,9901\nR,1,100\nR,2,300\nN,1\nN,2,1\nN,3,2\n"
         "TYPE,1\nREAL,1\nE,1,2\nTYPE,2\nREAL,2\nE,2,3\n"
         "D,1,ALL\nD,2,UY,,,3,,UZ,ROTX,ROTY,ROTZ\nD,1,UY\nF,3,FX,30\nFINISH\n/SOLU\nANTYPE,STATIC\n"
         "SOLVE\nFINISH\n";
  }
  const auto run = testing::run_deck_in(deck, dir);
  const auto u2 = run.reader->nodal_series(2, "UX");
  const auto u3 = run.reader->nodal_series(3, "UX");
  ASSERT_EQ(u3.size(), 1u);
  EXPECT_NEAR(u2.back().second, 0.3, 1e-12);
  EXPECT_NEAR(u3.back().second, 0.4, 1e-12);
  EXPECT_NEAR(run.reader->element_series(2, "FORC").back().second, 30.0, 1e-9);
  // The reader's validation comes from the registration: a missing real set is refused.
  std::ofstream(deck) << "/PREP7\nET,1,TSPRING\nN,1\nN,2,1\nE,1,2\nFINISH\n/SOLU\nSOLVE\n";
  try {
    read_deck(deck);
    FAIL() << "a TSPRING without real constants was accepted";
  } catch (const InputError& e) {
    EXPECT_NE(std::string(e.what()).find("real constant set 1 is not defined"), std::string::npos)
        << e.what();
  }
  std::filesystem::remove_all(dir);
}

TEST(ElementRegistry, TheMesherTheReportAndTheVtkExportTakeATestElementFromItsRegistration) {
  // Two bars of TSPRING meshed on lines by LMESH (the mesher asks the registered cell for its
  // dimension), joined by a TGAP: the report draws the bars as lines, knows TGAP as a gap (its
  // nodes picked for the nodal figures; the bars stay two bodies) and the VTK export writes
  // line cells — with no line of the mesher, the report or the export naming these types.
  const auto dir = testing::fresh_directory("element_registry_topology");
  const std::string deck = (dir / "tgap.inp").string();
  std::ofstream(deck)
      << "/PREP7\nET,1,TSPRING\nET,2,TGAP\nR,1,100\nK,1\nK,2,1\nK,3,2\nK,4,3\nL,1,2\nL,3,4\n"
         "LESIZE,ALL,,,2\nTYPE,1\nREAL,1\nLMESH,ALL\nTYPE,2\nE,NODE(1,0,0),NODE(2,0,0)\n"
         "FINISH\n/SOLU\nANTYPE,STATIC\nD,ALL,ALL\nDDELE,NODE(3,0,0),UX\n"
         "F,NODE(3,0,0),FX,1\nSOLVE\nFINISH\n";
  const auto run = testing::run_deck_in(deck, dir);
  const ReportMesh mesh = build_report_mesh(*run.reader);
  EXPECT_EQ(mesh.lines.size(), 2u * 5u);  // 4 bar elements and the gap
  EXPECT_TRUE(mesh.triangles.empty());
  EXPECT_TRUE(mesh.points.empty());
  EXPECT_EQ(mesh.gap_nodes.size(), 2u);
  ASSERT_EQ(mesh.bodies.size(), 2u);  // the gap joins no bodies
  EXPECT_EQ(mesh.bodies[0].name, "the TSPRING type 1 mat 1 real 1 part 1");
  EXPECT_TRUE(is_gap_type("TGAP"));
  EXPECT_FALSE(is_gap_type("TSPRING"));
  const VtkMesh vtk = build_vtk_mesh(*run.reader);
  ASSERT_EQ(vtk.n_cells(), 5u);
  for (unsigned char t : vtk.types) EXPECT_EQ(t, static_cast<unsigned char>(VtkCell::Line));
  std::filesystem::remove_all(dir);
}

TEST(ElementRegistry, ARoleMustFitTheCell) {
  ElementTypeDescriptor d = *find_element_type("TSPRING");
  d.name = "TSPRING3";
  d.number = 9903;
  d.role = ShapeRole::Solid;  // a line cell is no solid
  EXPECT_THROW(register_element_type(d), InternalError);
  d.role = ShapeRole::Line;
  d.faces = {{0, 2}};  // node position 2 of a 2-node element
  EXPECT_THROW(register_element_type(d), InternalError);
}

TEST(ElementRegistry, TheHexahedronFacesAreOutwardAndTheBrickNumbersThemAsMapdl) {
  // The unit cube I..P (z = 0 then z = 1, counter-clockwise from above): every face of the one
  // table is outward by the right-hand rule, every edge bounds exactly two faces.
  const std::vector<Vec3> x = {{0, 0, 0}, {1, 0, 0}, {1, 1, 0}, {0, 1, 0},
                               {0, 0, 1}, {1, 0, 1}, {1, 1, 1}, {0, 1, 1}};
  const CellTopology& hex = cell_topology(VtkCell::Hexahedron);
  ASSERT_EQ(hex.faces.size(), 6u);
  EXPECT_EQ(hex.edges.size(), 12u);
  const Vec3 centre(0.5, 0.5, 0.5);
  for (const auto& f : hex.faces) {
    const Vec3 n = (x[f[1]] - x[f[0]]).cross(x[f[2]] - x[f[1]]);
    EXPECT_GT(n.dot(x[f[0]] - centre), 0.0);
  }
  for (const auto& e : hex.edges) {
    int faces = 0;
    for (const auto& f : hex.faces)
      for (std::size_t k = 0; k < 4; ++k)
        if ((f[k] == e[0] && f[(k + 1) % 4] == e[1]) || (f[k] == e[1] && f[(k + 1) % 4] == e[0]))
          ++faces;
    EXPECT_EQ(faces, 2);
  }
  // SOLID185 faces (MAPDL element reference): J-I-L-K, I-J-N-M, J-K-O-N, K-L-P-O, L-I-M-P,
  // M-N-O-P, node order = SFE VALUE1..4.
  const std::vector<std::vector<int>> mapdl = {{1, 0, 3, 2}, {0, 1, 5, 4}, {1, 2, 6, 5},
                                               {2, 3, 7, 6}, {3, 0, 4, 7}, {4, 5, 6, 7}};
  EXPECT_EQ(find_element_type("SOLID185")->faces, mapdl);
  EXPECT_EQ(find_element_type("SOLID45")->faces, mapdl);
}

TEST(ElementRegistry, EveryBuiltInTypeHasTheRoleOfItsKind) {
  const std::map<std::string, ShapeRole> roles = {
      {"SOLID185", ShapeRole::Solid},   {"SHELL181", ShapeRole::Shell},
      {"BEAM188", ShapeRole::Line},     {"LINK180", ShapeRole::Line},
      {"COMBIN14", ShapeRole::Line},    {"MASS21", ShapeRole::Point},
      {"COMBIN40", ShapeRole::Gap},     {"CONTA178", ShapeRole::Gap},
      {"CONTA174", ShapeRole::Contact}, {"CONTA175", ShapeRole::Contact},
      {"TARGE170", ShapeRole::Target},  {"MATRIX50", ShapeRole::Superelement}};
  for (const auto& [name, role] : roles) EXPECT_EQ(find_element_type(name)->role, role) << name;
}

TEST(ElementRegistry, TheSupportedListAndLookupsComeFromTheRegistrations) {
  EXPECT_NE(supported_element_type_names().find("TSPRING"), std::string::npos);
  EXPECT_EQ(find_element_type("tspring"), find_element_type("9901"));
  EXPECT_EQ(find_element_type("tspring")->vtk_cell, VtkCell::Line);
  EXPECT_EQ(find_element_type("NOSUCH"), nullptr);
  EXPECT_EQ(find_element_type("8")->name, "LINK8");
  EXPECT_EQ(find_element_type("link180")->name, "LINK180");
}

TEST(ElementRegistry, RegisteringANameTwiceIsAnInternalError) {
  ElementTypeDescriptor twice = *find_element_type("TSPRING");
  EXPECT_THROW(register_element_type(twice), InternalError);
  twice.name = "TSPRING2";  // new name, but the number 9901 is taken
  EXPECT_THROW(register_element_type(twice), InternalError);
}

// ---- built-in registrations against their classes -----------------------------------------

/// A small model with one element of `type`, enough to construct it.
Model one_element_model(const std::string& type) {
  Model m;
  const CellTopology& cell = cell_topology(find_element_type(type)->vtk_cell);
  // A tetrahedron's four corners must not lie in one plane; midside nodes at mid-edge.
  const std::vector<Vec3> corners =
      cell.corner_nodes == 4 && cell.dimension == 3
          ? std::vector<Vec3>{{0, 0, 0}, {1, 0, 0}, {0, 1, 0}, {0, 0, 1}}
          : std::vector<Vec3>{{0, 0, 0}, {1, 0, 0}, {1, 1, 0}, {0, 1, 0},
                              {0, 0, 1}, {1, 0, 1}, {1, 1, 1}, {0, 1, 1}};
  for (int i = 0; i < static_cast<int>(corners.size()); ++i)
    m.nodes[i + 1] = Node{i + 1, corners[static_cast<std::size_t>(i)]};
  for (int k = 0; k < cell.midside_nodes; ++k) {
    const auto& e = cell.edges[static_cast<std::size_t>(k)];
    const int id = cell.corner_nodes + k + 1;
    m.nodes[id] = Node{id, 0.5 * (corners[static_cast<std::size_t>(e[0])] +
                                  corners[static_cast<std::size_t>(e[1])])};
  }
  ElementType et;
  et.id = 1;
  et.ansys_name = type;
  m.element_types[1] = et;
  // 0.1 at each real constant the type reads (element_fields.h refuses the others); a flag
  // such as LINK180's TENSKEY stays 0.
  RealSet real{1, std::vector<double>(6, 0.0)};
  if (const ElementFields* fields = element_fields(type))
    for (const auto& c : fields->real_constants)
      if (c.position <= 6 && !c.refused && c.name != "TENSKEY")
        real.values[static_cast<std::size_t>(c.position - 1)] = 0.1;
  m.real_sets[1] = real;
  Material mat;
  mat.id = 1;
  mat.props = {{"EX", 1e6}, {"NUXY", 0.3}, {"PRXY", 0.3}, {"DENS", 1e-3}};
  m.materials[1] = mat;
  const ElementTypeDescriptor& d = *find_element_type(type);
  ElementRecord r;
  r.id = 1;
  for (int i = 0; i < d.n_nodes; ++i) r.nodes.push_back(i + 1);
  if (d.accepts_section("BEAM")) {
    m.sections[1] = Section{1, "BEAM", "RECT", {0.1, 0.1}};
    r.secnum = 1;
  }
  // A shell that reads its thickness from a section only (SHELL208): one layer 0.1 thick.
  const ElementFields* fields = element_fields(type);
  if (d.accepts_section("SHELL") && (fields == nullptr || fields->real_constants.empty())) {
    m.sections[1] = Section{1, "SHELL", "", {0.1}, {{0.1}}, ""};
    r.secnum = 1;
  }
  m.elements[1] = r;
  return m;
}

TEST(ElementRegistry, EveryBuiltInTypeMatchesItsElementClass) {
  int checked = 0;
  for (const ElementTypeDescriptor* d : registered_element_types()) {
    if (d->defined_by_file || d->family == "AxialTestSpring") continue;  // MATRIX50: a file
    // Explicit-only types (SOLID164) have no implicit element: their sets are checked against
    // the registration in ExplicitSolid.SetMatchesItsRegistration (test_explicit_dynamics.cpp).
    if (d->explicit_set) continue;
    // Contact pairs need a partner (a target, a pilot, stiffness at the nodes): built and
    // checked against their registration in test_contact.cpp (CONTA174:
    // test_contact_generation.cpp; the 2-D ones: test_contact_2d.cpp).
    if (d->name == "CONTA174" || d->name == "CONTA175" || d->name == "CONTA178" ||
        d->name == "TARGE170" || d->name == "CONTA171" || d->name == "CONTA172" ||
        d->name == "TARGE169")
      continue;
    SCOPED_TRACE(d->name);
    const Model m = one_element_model(d->name);
    const auto e = create_element(ElementBuildContext{m, {}}, m.elements.at(1));
    // A layered shell type registers its layered elements' names (SHELL181, SHELL281): a
    // homogeneous element's names are their beginning, the same columns first.
    const auto& names = e->result_names();
    if (d->name == "SHELL181" || d->name == "SHELL281") {
      ASSERT_LT(names.size(), d->result_names.size());
      EXPECT_TRUE(std::equal(names.begin(), names.end(), d->result_names.begin()));
      EXPECT_EQ(d->result_names[names.size()], "SX_L1_TOP");
    } else {
      EXPECT_EQ(names, d->result_names);
    }
    EXPECT_EQ(e->family(), d->family);
    if (e->has_status()) EXPECT_TRUE(d->has_status);
    EXPECT_GE(d->number, 1);
    ++checked;
  }
  // LINK1 LINK8 LINK180 COMBIN14 MASS21 COMBIN40 SHELL63/181 SOLID45/185 SOLID186/187 BEAM188
  // BEAM189 BEAM4 BEAM3 PLANE182/183 PLANE42/82 SHELL281 SHELL208 MPC184 MESH200 SOLID95/92
  EXPECT_EQ(checked, 26);
}

}  // namespace
}  // namespace impactfe::test_element_registry
