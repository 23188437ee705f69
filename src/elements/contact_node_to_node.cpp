/// CONTA178 node-to-node contact (APDL_MODELING §8.4): the modern successor of the COMBIN40 gap.
/// Nodes I, J with UX, UY, UZ; the contact normal n from I towards J (the real constants NX, NY,
/// NZ when given, otherwise the node locations) and the gap g = GAP + n·(u_J − u_I), GAP from the
/// node locations when blank. The contact law (penalty / augmented Lagrange, Coulomb friction,
/// KEYOPT(12) behaviour) is elements/contact_point.h.
#include <fmt/format.h>

#include <Eigen/Dense>
#include <algorithm>
#include <cmath>

#include "elements/contact_point.h"
#include "elements/element_registry.h"
#include "elements/line_element_data.h"

namespace impactfe {

namespace {

constexpr const char* kNodeToNodeFamily = "NodeToNodeContact";

class NodeToNodeContact final : public ContactPoint {
 public:
  NodeToNodeContact(int id, int node_i, int node_j, const ContactLawData& data)
      : ContactPoint(id, node_i, node_j, data) {
    initialize();
  }
  const char* family() const override { return kNodeToNodeFamily; }
};

std::unique_ptr<Element> make_node_to_node_contact(const ElementBuildContext& ctx,
                                                   const ElementRecord& record) {
  const Model& model = ctx.model;
  const ElementType& type = line_data::element_type(model, record);
  const auto [ni, nj] = line_data::distinct_node_pair(model, record, kNodeToNodeFamily);
  const auto fail = [&](const std::string& what) {
    return InputError(record.where, fmt::format("element {} (CONTA178): {}", record.id, what));
  };
  for (int k = 1; k < static_cast<int>(type.keyopt.size()); ++k)
    if (k != 2 && k != 12 && type.key(k) != 0)
      throw fail(
          fmt::format("KEYOPT({}) = {} is not supported (impactfe reads KEYOPT(2) "
                      "algorithm and KEYOPT(12) behaviour; the others must be 0)",
                      k, type.key(k)));
  ContactLawData data;
  const int algorithm = type.key(2);
  if (algorithm != 0 && algorithm != 1)
    throw fail(
        fmt::format("KEYOPT(2) = {} is not supported (0 augmented Lagrange, 1 penalty; "
                    "MPC and Lagrange multipliers are not available)",
                    algorithm));
  data.augmented = algorithm == 0;
  const int behaviour = type.key(12);
  if (behaviour < 0 || behaviour > 6)
    throw fail(fmt::format("KEYOPT(12) = {} is not a contact behaviour (0..6)", behaviour));
  data.behaviour = static_cast<ContactBehaviour>(behaviour);

  const RealSet& real = line_data::real_set(model, record, kNodeToNodeFamily);
  // Real constants: 1 FKN, 2 GAP, 3 START, 4 FKS, 5 REDFACT, 6-8 NX NY NZ, 9 TOLN [A].
  for (int i = 10; i <= static_cast<int>(real.values.size()); ++i)
    if (real.get(i) != 0.0)
      throw fail(
          fmt::format("real constant {} of set {} is not read (1 FKN, 2 GAP, 3 START, "
                      "4 FKS, 6-8 NX NY NZ, 9 TOLN)",
                      i, record.real));
  if (real.get(5) != 0.0) throw fail("REDFACT (real constant 5) is not supported: leave blank");
  const Vec3 given(real.get(6), real.get(7), real.get(8));
  const Vec3 ij = nj.x - ni.x;
  if (given.norm() > 0.0)
    data.normal = given.normalized();
  else if (ij.norm() > 0.0)
    data.normal = ij.normalized();
  else
    throw fail(
        fmt::format("nodes {} and {} coincide: give the contact normal NX, NY, NZ (real "
                    "constants 6-8 of set {})",
                    ni.id, nj.id, record.real));
  data.gap0 = real.get(2) != 0.0 ? real.get(2) : data.normal.dot(ij);
  data.start = real.get(3) > 0.0 ? 1 : real.get(3) < 0.0 ? -1 : 0;
  data.toln = real.get(9);
  if (data.toln < 0.0) throw fail("TOLN (real constant 9) must not be negative");

  const double fkn = real.get(1) != 0.0 ? real.get(1) : 1.0;
  if (fkn < 0.0) {
    data.kn = -fkn;
  } else {
    // A factor on the stiffness of the structure at the two nodes along n (the softer side).
    const double si = attached_stiffness(ctx, ni.id, data.normal);
    const double sj = attached_stiffness(ctx, nj.id, data.normal);
    const double base = si > 0.0 && sj > 0.0 ? std::min(si, sj) : std::max(si, sj);
    if (!(base > 0.0))
      throw fail(
          "FKN > 0 is a factor on the stiffness of the elements at the nodes, and none "
          "is attached: give an absolute stiffness as a negative FKN");
    data.kn = fkn * base;
  }
  const double fks = real.get(4);
  data.kt = fks != 0.0 ? std::abs(fks) : data.kn;

  const auto mat = model.materials.find(record.mat);
  data.mu = mat == model.materials.end() ? 0.0 : mat->second.get("MU", 0.0);
  if (data.mu < 0.0) throw fail(fmt::format("MU of material {} is negative", record.mat));
  return std::make_unique<NodeToNodeContact>(record.id, ni.id, nj.id, data);
}

const ElementRegistration kConta178{{.name = "CONTA178",
                                     .number = 178,
                                     .family = kNodeToNodeFamily,
                                     .n_nodes = 2,
                                     .real_constants = RealConstantUse::Required,
                                     .vtk_cell = VtkCell::Line,
                                     .role = ShapeRole::Gap,
                                     .result_names = ContactPoint::names(),
                                     .result_sequences = ContactPoint::sequences(),
                                     .has_status = true,
                                     .create = make_node_to_node_contact}};

}  // namespace

}  // namespace impactfe
