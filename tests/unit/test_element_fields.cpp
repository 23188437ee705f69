// Every real constant and KEYOPT value an element type declares (elements/element_fields.h) is
// carried out, and everything else is refused. The test walks the element registry: each type
// has a declaration; for each declared field a one-element model is built with the field at a
// probe value and compared with the same model without it (stiffness, internal force, both
// masses, damping and results at a probe displacement, after a status update): the element must
// change, or the field must be refused, or be listed below with the reason it cannot change this
// element (and the test where it is checked). Undeclared KEYOPTs and real constants are refused.
#include <fmt/format.h>
#include <gtest/gtest.h>

#include <cmath>
#include <map>
#include <set>

#include "deck/deck_reader.h"
#include "elements/element.h"
#include "elements/element_fields.h"
#include "elements/element_registry.h"

namespace impactfe::test_element_fields {
namespace {

/// A one-element model of a type: the deck up to (not including) its real set, the real set
/// values (R,1,... with RMORE beyond six), and the element command.
struct Probe {
  std::string head;
  std::vector<double> real;
  std::string element;
  /// Another element command under a KEYOPT that changes what E takes (key: the KEYOPT line).
  std::map<std::string, std::string> element_with = {};
  /// The KEYOPT under which the type reads its real set at all (checks of undeclared ones).
  std::string reads_real_with = {};
};

std::string real_commands(const std::vector<double>& values) {
  std::string out;
  for (std::size_t i = 0; i < values.size(); i += 6) {
    out += i == 0 ? "R,1" : "RMORE";
    for (std::size_t j = i; j < std::min(values.size(), i + 6); ++j)
      out += fmt::format(",{}", values[j]);
    out += "\n";
  }
  return out;
}

const std::string kMaterial = "MP,EX,1,2E5\nMP,NUXY,1,0.3\nMP,DENS,1,7.8E-3\n";

/// MESH200: a cell of each KEYOPT(1) shape on the 20 nodes of a brick (E, then EMORE).
Probe mesh200_probe(const std::string& cube) {
  const int nodes[] = {2, 3, 2, 3, 3, 6, 4, 8, 4, 10, 8, 20};
  const auto element = [](int n) {
    std::string out = "E";
    for (int k = 1; k <= n; ++k) out += (k == 9 || k == 17 ? "\nEMORE," : ",") + std::to_string(k);
    return out;
  };
  Probe p{cube +
              "N,9,0.5,0,0\nN,10,1,0.6,0\nN,11,0.5,1.1,0\nN,12,0,0.5,0\nN,13,0.5,0,1.05\n"
              "N,14,1,0.5,1.05\nN,15,0.5,1,1\nN,16,0,0.5,1\nN,17,0,0,0.5\nN,18,1,0,0.55\n"
              "N,19,1,1.1,0.5\nN,20,0,1,0.5\n",
          {},
          element(2)};
  for (int v = 1; v <= 11; ++v)
    p.element_with[fmt::format("KEYOPT,1,1,{}\n", v)] = element(nodes[v]);
  return p;
}

std::map<std::string, Probe> probes() {
  const std::string cube =
      "N,1,0,0,0\nN,2,1,0,0\nN,3,1,1.2,0\nN,4,0,1,0\nN,5,0,0,1\nN,6,1,0,1.1\nN,7,1,1,1\n"
      "N,8,0,1,1\n";
  const std::string plate = "N,1,0,0,0\nN,2,2,0,0\nN,3,2,1.5,0.1\nN,4,0,1.5,0\n";
  std::vector<double> shell(19, 0.0);
  shell[0] = shell[1] = shell[2] = shell[3] = 0.1;
  std::map<std::string, Probe> all = {
      {"LINK1", {"N,1,0,0\nN,2,3,4\n", {2.0, 0.0}, "E,1,2"}},
      {"LINK8", {"N,1,0,0,0\nN,2,3,4,12\n", {2.0, 0.0}, "E,1,2"}},
      {"LINK180", {"N,1,0,0,0\nN,2,3,4,12\n", {2.0, 0.0, 0.0}, "E,1,2"}},
      {"BEAM3", {"N,1,0,0\nN,2,3,4\n", {2.0, 1.5, 1.0, 0.0, 0.0, 0.0}, "E,1,2"}},
      {"BEAM4",
       {"N,1,0,0,0\nN,2,3,4,12\n",
        {2.0, 1.5, 1.2, 1.0, 0.8, 0.0, 0.0, 0.0, 0.0, 0.0, 0.0, 0.0},
        "E,1,2"}},
      {"BEAM188",
       {"SECTYPE,1,BEAM,RECT\nSECDATA,1,2\nN,1,0,0,0\nN,2,3,4,12\n", {}, "SECNUM,1\nE,1,2"}},
      {"BEAM189",
       {"SECTYPE,1,BEAM,RECT\nSECDATA,1,2\nN,1,0,0,0\nN,2,3,4,12\nN,3,1.5,2.2,6\n",
        {},
        "SECNUM,1\nE,1,2,3"}},
      {"COMBIN14", {"N,1,0,0,0\nN,2,1,2,0\n", {100.0, 5.0, 0.0}, "E,1,2"}},
      {"COMBIN40", {"N,1,0,0,0\nN,2,1,0,0\n", {100.0, 2.0, 3.0, 0.0, 0.0, 50.0}, "E,1,2"}},
      {"MASS21", {"N,1,0,0,0\n", {1.0, 1.0, 1.0, 0.5, 0.5, 0.5}, "E,1"}},
      {"MPC184", {"N,1,0,0,0\nN,2,1,2,0\n", {}, "E,1,2"}},
      {"SOLID45", {cube, {}, "E,1,2,3,4,5,6,7,8"}},
      {"SOLID185", {cube, {}, "E,1,2,3,4,5,6,7,8"}},
      {"SOLID186",
       {cube + "N,9,0.5,0,0\nN,10,1,0.6,0\nN,11,0.5,1.1,0\nN,12,0,0.5,0\nN,13,0.5,0,1.05\nN,14,1,0."
               "5,1.05\nN,15,0.5,1,1\nN,16,0,0.5,1\nN,17,0,0,0.5\nN,18,1,0,0.55\nN,19,1,1.1,0.5\nN,"
               "20,0,1,0.5\n",
        {},
        "E,1,2,3,4,5,6,7,8\nEMORE,9,10,11,12,13,14,15,16\nEMORE,17,18,19,20"}},
      {"SOLID187",
       {"N,1,0,0,0\nN,2,1,0,0\nN,3,0.1,1.2,0\nN,4,0,0.1,1.1\nN,5,0.5,0,0\nN,6,0.55,0.6,0\nN,7,0.05,"
        "0.6,0\nN,8,0,0.05,0.55\nN,9,0.5,0.05,0.55\nN,10,0.05,0.65,0.55\n",
        {},
        "E,1,2,3,4,5,6,7,8\nEMORE,9,10"}},
      {"SHELL63", {plate, shell, "E,1,2,3,4"}},
      {"MESH200", mesh200_probe(cube)},
      {"SHELL181", {plate, {0.1, 0.1, 0.1, 0.1}, "E,1,2,3,4"}},
      {"SHELL281",
       {"N,1,0,0\nN,2,2,0\nN,3,2.2,1.5\nN,4,0,1.4\nN,5,1,0\nN,6,2.1,0.75\nN,7,1.1,1.45\n"
        "N,8,0,0.7\n",
        {0.1, 0.12, 0.14, 0.16},
        "E,1,2,3,4,5,6,7,8"}},
      // An axisymmetric cone segment: both radial and axial extent, so membrane, bending and
      // hoop terms all act.
      {"SHELL208", {"SECTYPE,1,SHELL\nSECDATA,0.1\nN,1,1,0\nN,2,2,1.5\n", {}, "SECNUM,1\nE,1,2"}},
      {"PLANE182",
       {"N,1,0,0\nN,2,2,0\nN,3,2.2,1.5\nN,4,0,1.4\n", {0.1}, "E,1,2,3,4", {}, "KEYOPT,1,3,3\n"}},
      // The 6-node triangle (K = L = O), so that KEYOPT(1) = 1 (the triangle form, E with
      // I J K L M N) applies. Both read THK only in plane stress with thickness (KEYOPT(3) = 3).
      {"PLANE183",
       {"N,1,0,0\nN,2,2,0\nN,3,0.2,1.5\nN,4,1,0.05\nN,5,1.1,0.75\nN,6,0.1,0.75\n",
        {0.1},
        "E,1,2,3,3,4,5,3,6",
        {{"KEYOPT,1,1,1\n", "E,1,2,3,4,5,6"}},
        "KEYOPT,1,3,3\n"}},
  };
  all["PLANE42"] = all.at("PLANE182");  // the legacy plane solids: computed as PLANE182 / 183
  all["PLANE42"].element_with.clear();
  all["PLANE82"] = all.at("PLANE183");
  all["PLANE82"].element_with.clear();
  all["SOLID95"] = all.at("SOLID186");  // the legacy solids: computed as SOLID186 / SOLID187
  all["SOLID92"] = all.at("SOLID187");
  return all;
}

/// Fields that cannot change a one-element model by design, with the reason and where the
/// field's effect is checked instead. Key "TYPE R<position>" or "TYPE K<number>=<value>".
const std::map<std::string, std::string>& by_design() {
  static const std::map<std::string, std::string> m = [] {
    std::map<std::string, std::string> out = {
        {"LINK1 K1=1",
         "an option of the thesis's ANSYS 4 decks with no effect on LINK1 (their "
         "results: DeckThesis.*, ReferenceSection2.*)"},
        {"COMBIN40 K1=1", "lock-up acts once the gap has closed (CombinationGap.*)"},
        {"COMBIN40 R5", "FSLIDE acts while sliding (CombinationGap.*)"},
        {"COMBIN40 K3=1", "KEYOPT(3) 0 and 1 both choose UX (MAPDL's numbering)"},
        {"SHELL63 K5=1", "a printout option of the thesis's ANSYS 4 decks (helmet_full.inp)"},
        {"SOLID45 K2=1",
         "reduced integration is approximated by full 2x2x2 integration (warned; "
         "docs/elements/solid45.md)"},
        {"SHELL181 K3=2", "both integrations are computed with the SHELL63 kernel's extra shapes"},
        {"SHELL181 K8=1", "layer data storage: a printout option (docs/elements/shell181.md)"},
        {"SHELL181 K8=2", "layer data storage: a printout option (docs/elements/shell181.md)"},
        {"SHELL208 K8=1", "layer data storage: a printout option (docs/elements/shell208.md)"},
        {"SHELL208 K8=2", "layer data storage: a printout option (docs/elements/shell208.md)"},
        {"PLANE42 K5=1", "a printout option (docs/elements/plane182.md, legacy forms)"},
        {"PLANE42 K5=2", "a printout option (docs/elements/plane182.md, legacy forms)"},
        {"PLANE42 K6=1", "a printout option (docs/elements/plane182.md, legacy forms)"},
        {"PLANE42 K6=2", "a printout option (docs/elements/plane182.md, legacy forms)"},
        {"PLANE42 K6=3", "a printout option (docs/elements/plane182.md, legacy forms)"},
        {"PLANE42 K6=4", "a printout option (docs/elements/plane182.md, legacy forms)"},
        {"PLANE82 K5=1", "a printout option (docs/elements/plane182.md, legacy forms)"},
        {"PLANE82 K5=2", "a printout option (docs/elements/plane182.md, legacy forms)"},
        {"PLANE82 K6=1", "a printout option (docs/elements/plane182.md, legacy forms)"},
        {"PLANE82 K6=2", "a printout option (docs/elements/plane182.md, legacy forms)"},
        {"PLANE82 K6=3", "a printout option (docs/elements/plane182.md, legacy forms)"},
        {"PLANE82 K6=4", "a printout option (docs/elements/plane182.md, legacy forms)"},
        {"SHELL281 K8=1", "layer data storage: a printout option (docs/elements/shell281.md)"},
        {"SHELL281 K8=2", "layer data storage: a printout option (docs/elements/shell281.md)"},
        {"BEAM188 K3=2",
         "the element is exact for end loads with any interpolation "
         "(docs/elements/beam.md, KEYOPT(3))"},
        {"BEAM188 K3=3",
         "the element is exact for end loads with any interpolation "
         "(docs/elements/beam.md, KEYOPT(3))"},
        {"LINK180 K2=1",
         "the area is held constant under either value (KEYOPT(2) = 1 is exactly that; the "
         "default's incompressible section agrees to first order in the strain)"},
        {"PLANE182 R1",
         "THK acts with KEYOPT(3) = 3 only (checked by K3=3 here); otherwise unit thickness, as "
         "in MAPDL"},
        {"PLANE42 R1",
         "THK acts with KEYOPT(3) = 3 only (checked by K3=3 here); otherwise unit thickness, as "
         "in MAPDL"},
        {"PLANE82 R1",
         "THK acts with KEYOPT(3) = 3 only (checked by K3=3 here); otherwise unit thickness, as "
         "in MAPDL"},
        {"PLANE183 R1",
         "THK acts with KEYOPT(3) = 3 only (checked by K3=3 here); otherwise unit thickness, as "
         "in MAPDL"},
        {"PLANE183 K1=1",
         "the triangle form takes the 6-node triangle's nodes from E,I,J,K,L,M,N and numbers its "
         "faces 1-3 (face 3 is I-K): the same element; the faces act through SFE pressures"},
        {"MPC184 K2=1",
         "Lagrange multipliers are solved by elimination as well: the same constraint equations "
         "(docs/elements/mpc184.md; ConstraintEquations.*)"},
        {"MASS21 K2=1",
         "masses in nodal axes equal global ones on an unrotated node; refused on a "
         "rotated one (AcceptedFields-style check below)"},
    };
    // MESH200's KEYOPT(1) chooses the cell of a mesh-only element: no stiffness in any
    // (CdbArchives.Mesh200CellsAreCheckedByKeyopt checks the node counts it takes).
    for (int v = 1; v <= 11; ++v)
      out[fmt::format("MESH200 K1={}", v)] = "the cell of a mesh-only element, without stiffness";
    return out;
  }();
  return m;
}

/// Contact types: their fields act through a contact pair, checked by the contact tests.
const std::set<std::string> kContactTypes = {"CONTA171", "CONTA172", "CONTA174", "CONTA175",
                                             "CONTA178", "TARGE169", "TARGE170", "MATRIX50"};

Model model_of(const std::string& type, const Probe& p, const std::vector<double>& real,
               const std::string& keyopts) {
  const std::string deck =
      "/PREP7\nET,1," + type + "\n" + keyopts + kMaterial + p.head +
      (real.empty() ? std::string() : real_commands(real)) +
      (p.element_with.count(keyopts) ? p.element_with.at(keyopts) : p.element) + "\nFINISH\n";
  return read_deck_text(deck, "probe.inp").model;
}

/// What the element computes at a probe displacement (status updated first).
std::vector<double> fingerprint(const Model& model) {
  auto e = create_element(ElementBuildContext{model, {}}, model.elements.begin()->second);
  const int n = e->n_dofs();
  Eigen::VectorXd u(n), v(n);
  for (int i = 0; i < n; ++i) {
    u(i) = 1e-3 * std::sin(1.0 + 0.7 * i);
    v(i) = 1e-2 * std::cos(0.3 + 0.4 * i);
  }
  ElementContext ctx;
  std::vector<double> out{static_cast<double>(n)};
  for (const DofKey& key : e->dofs())  // which DOFs (a torsional spring's are rotations)
    out.insert(out.end(), {static_cast<double>(key.node), static_cast<double>(key.dof)});
  const auto add = [&out](const Eigen::MatrixXd& m) {
    out.insert(out.end(), m.data(), m.data() + m.size());
  };
  if (e->has_status()) e->update_status(ctx, u);
  Eigen::MatrixXd k, m, c;
  Eigen::VectorXd f;
  e->tangent(ctx, u, k, f);
  add(k);
  add(f);
  e->mass(ctx, m);
  add(m);
  ctx.lumped_mass = true;
  e->mass(ctx, m);
  add(m);
  ctx.lumped_mass = false;
  e->damping(ctx, u, c);
  add(c);
  ElementResultValues r;
  e->results(ctx, u, v, r);
  out.insert(out.end(), r.begin(), r.end());
  return out;
}

bool same(const std::vector<double>& a, const std::vector<double>& b) {
  if (a.size() != b.size()) return false;
  for (std::size_t i = 0; i < a.size(); ++i)
    if (!(std::abs(a[i] - b[i]) <= 1e-12 * (1.0 + std::abs(a[i])))) return false;
  return true;
}

TEST(ElementFields, EveryRegisteredTypeDeclaresItsFields) {
  std::set<std::string> registered;
  for (const auto* d : registered_element_types()) {
    registered.insert(d->name);
    if (d->name == "TSPRING" || d->name == "TGAP") continue;  // test_element_registry.cpp's
    EXPECT_NE(element_fields(d->name), nullptr) << d->name << " declares no fields";
  }
  for (const auto& f : all_element_fields())
    EXPECT_TRUE(registered.count(f.type)) << f.type << " is declared but not registered";
}

TEST(ElementFields, EveryDeclaredFieldActsOrIsRefused) {
  const auto all = probes();
  int checked = 0;
  for (const auto& fields : all_element_fields()) {
    if (kContactTypes.count(fields.type)) continue;
    // Explicit-only types are not built by the implicit path this test drives; their fields
    // are checked by ExplicitSolid.KeyoptionsOfSolid164 (test_explicit_dynamics.cpp).
    if (const auto* d = find_element_type(fields.type); d && d->explicit_set) continue;
    ASSERT_TRUE(all.count(fields.type)) << fields.type << " has no probe model in this test";
    const Probe& p = all.at(fields.type);
    const auto base = fingerprint(model_of(fields.type, p, p.real, ""));
    const auto check = [&](const std::string& key, const std::vector<double>& real,
                           const std::string& keyopts, bool refused) {
      SCOPED_TRACE(key);
      ++checked;
      std::vector<double> varied;
      try {
        varied = fingerprint(model_of(fields.type, p, real, keyopts));
      } catch (const InputError& e) {
        EXPECT_TRUE(refused) << key << " was refused: " << e.what();
        return;
      }
      EXPECT_FALSE(refused) << key << " is declared refused but was accepted";
      if (by_design().count(key)) {
        EXPECT_TRUE(same(base, varied)) << key << " is listed as without effect, but acts";
      } else {
        EXPECT_FALSE(same(base, varied)) << key << " changes nothing: silently ignored";
      }
    };
    for (const auto& rc : fields.real_constants) {
      std::vector<double> real = p.real;
      if (real.size() < static_cast<std::size_t>(rc.position))
        real.resize(static_cast<std::size_t>(rc.position), 0.0);
      double& value = real[static_cast<std::size_t>(rc.position - 1)];
      value = rc.name == "TENSKEY" ? 1.0 : value != 0.0 ? 1.7 * value : 0.37;
      check(fmt::format("{} R{}", fields.type, rc.position), real, "", rc.refused);
    }
    for (const auto& k : fields.keyopts)
      for (int v : k.values)
        if (v != 0)
          check(fmt::format("{} K{}={}", fields.type, k.number, v), p.real,
                fmt::format("KEYOPT,1,{},{}\n", k.number, v), false);
    // Not declared: refused. Every KEYOPT number without a declaration, and one real constant
    // beyond the declared ones.
    for (int number = 1; number <= 18; ++number) {
      const bool declared = std::any_of(fields.keyopts.begin(), fields.keyopts.end(),
                                        [&](const KeyoptField& k) { return k.number == number; });
      if (!declared)
        check(fmt::format("{} K{}=1", fields.type, number), p.real,
              fmt::format("KEYOPT,1,{},1\n", number), true);
    }
    if (!p.real.empty()) {
      int next = 1;
      for (const auto& rc : fields.real_constants) next = std::max(next, rc.position + 1);
      std::vector<double> real = p.real;
      real.resize(static_cast<std::size_t>(next), 0.0);
      real.back() = 0.5;
      check(fmt::format("{} R{} (not declared)", fields.type, next), real, p.reads_real_with, true);
    }
  }
  std::cout << checked << " fields checked\n";
}

TEST(ElementFields, ContactTypesDeclareWhatTheirElementsAccept) {
  // Their own checks (contact_node_to_node.cpp, target_surface.cpp) refuse the rest; the central
  // check must not refuse what they carry out, and refuses what is not declared.
  for (const std::string type :
       {"CONTA171", "CONTA172", "CONTA174", "CONTA175", "CONTA178", "TARGE169", "TARGE170"}) {
    const ElementFields* f = element_fields(type);
    ASSERT_NE(f, nullptr) << type;
    for (int number = 1; number <= 18; ++number) {
      ElementType t;
      t.ansys_name = type;
      t.keyopt[static_cast<std::size_t>(number)] = 1;
      const bool declared =
          std::any_of(f->keyopts.begin(), f->keyopts.end(), [&](const KeyoptField& k) {
            return k.number == number &&
                   std::find(k.values.begin(), k.values.end(), 1) != k.values.end();
          });
      EXPECT_EQ(keyopt_refusal(t).empty(), declared) << type << " KEYOPT(" << number << ")";
    }
  }
}

TEST(ElementFields, MassInNodalAxesOfARotatedNodeIsRefused) {
  const Probe p{"N,1,0,0,0,30\n", {1.0, 2.0, 3.0, 0.5, 0.5, 0.5}, "E,1"};
  EXPECT_THROW(fingerprint(model_of("MASS21", p, p.real, "KEYOPT,1,2,1\n")), InputError);
  EXPECT_NO_THROW(fingerprint(model_of("MASS21", p, p.real, "")));
}

}  // namespace
}  // namespace impactfe::test_element_fields
