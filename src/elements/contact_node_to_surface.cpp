/// CONTA175 node-to-surface contact against a rigid TARGE170 target (APDL_MODELING §8.4): one
/// contact node paired, through the shared real-constant set, with the rigid target of that set
/// (elements/target_surface.h). The element's DOFs are the pilot node's and the contact node's
/// UX, UY, UZ, fixed for the whole run, so the assembly pattern stays static. Before each status
/// update the contact search finds the nearest target facet the node projects into (bucket
/// grid, within the pinball) and sets the normal and gap of the point law
/// (elements/contact_point.h: penalty / augmented Lagrange, Coulomb friction, KEYOPT(12)).
/// Detection is at the contact node (KEYOPT(4) = 0..3 all give nodal detection).
#include <fmt/format.h>

#include <Eigen/Dense>
#include <cmath>

#include "elements/contact_point.h"
#include "elements/element_registry.h"
#include "elements/line_element_data.h"
#include "elements/target_surface.h"

namespace impactfe {

namespace {

constexpr const char* kFamily = "NodeToSurfaceContact";

class NodeToSurfaceContact final : public ContactPoint {
 public:
  NodeToSurfaceContact(int id, int node, const Vec3& x, std::shared_ptr<const TargetSurface> target,
                       double reach, double offset, const ContactLawData& data)
      : ContactPoint(id, target->pilot(), node, data),
        x_(x),
        target_(std::move(target)),
        reach_(reach),
        offset_(offset) {
    initialize();
  }
  const char* family() const override { return kFamily; }

 protected:
  /// The target point nearest to the contact node in the target's frame: y = X + u_node −
  /// u_pilot (the target translates with its pilot). g = distance − CNOF.
  bool locate(const Eigen::VectorXd& u) override {
    const Vec3 d(u(3) - u(0), u(4) - u(1), u(5) - u(2));
    const auto hit = target_->closest(x_ + d, reach_);
    if (!hit) return false;
    data_.normal = hit->normal;
    data_.gap0 = hit->gap - offset_ - hit->normal.dot(d);
    return true;
  }

 private:
  Vec3 x_;
  std::shared_ptr<const TargetSurface> target_;
  double reach_;   // pinball radius
  double offset_;  // CNOF
};

std::unique_ptr<Element> make_node_to_surface_contact(const ElementBuildContext& ctx,
                                                      const ElementRecord& record) {
  const Model& model = ctx.model;
  const ElementType& type = line_data::element_type(model, record);
  const Node& node = line_data::node(model, record, 0, 1, kFamily);
  const auto fail = [&](const std::string& what) {
    return InputError(record.where, fmt::format("element {} (CONTA175): {}", record.id, what));
  };
  for (int k = 1; k < static_cast<int>(type.keyopt.size()); ++k) {
    const int v = type.key(k);
    const bool ok = v == 0 || (k == 2 && v == 1) || (k == 4 && v <= 3) || (k == 10 && v <= 2) ||
                    (k == 12 && v <= 6);
    if (!ok || v < 0)
      throw fail(
          fmt::format("KEYOPT({}) = {} is not supported (KEYOPT(2) 0 augmented "
                      "Lagrange / 1 penalty, KEYOPT(4) 0-3 (nodal detection), KEYOPT(10) "
                      "0-2 (constant stiffness), KEYOPT(12) 0-6; the others 0)",
                      k, v));
  }
  ContactLawData data;
  data.augmented = type.key(2) == 0;
  data.behaviour = static_cast<ContactBehaviour>(type.key(12));

  const RealSet& real = line_data::real_set(model, record, kFamily);
  // 3 FKN, 4 FTOLN, 6 PINB, 10 CNOF, 12 FKT are read; 14 and beyond are thermal (ignored).
  for (int i : {1, 2, 5, 7, 8, 9, 11, 13})
    if (real.get(i) != 0.0)
      throw fail(
          fmt::format("real constant {} of set {} is not supported (impactfe reads 3 FKN, "
                      "4 FTOLN, 6 PINB, 10 CNOF, 12 FKT)",
                      i, record.real));
  std::shared_ptr<const TargetSurface> target = rigid_target(ctx, record);
  if (target->pilot() == node.id) throw fail("the contact node is the target's pilot node");

  const double depth = attached_depth(ctx, node.id);
  const auto length = [&](double value, double fallback, const char* name) {
    const double v = value != 0.0 ? value : fallback;
    if (v < 0.0) return -v;
    if (!(depth > 0.0))
      throw fail(
          fmt::format("{} is a factor on the depth of the underlying elements, and none "
                      "with a volume is attached to node {}: give it as a negative "
                      "(absolute) value",
                      name, node.id));
    return v * depth;
  };
  const double reach = length(real.get(6), 2.0, "PINB (real constant 6)");
  data.toln = real.get(4) < 0.0 || depth > 0.0 ? length(real.get(4), 0.1, "FTOLN") : 0.0;

  // The initial normal: the nearest facet within the pinball, else the first facet.
  const auto hit = target->closest(node.x, reach);
  const Vec3 n0 = hit ? hit->normal : target->triangles().front().normal;
  const double fkn = real.get(3) != 0.0 ? real.get(3) : 1.0;
  if (fkn < 0.0) {
    data.kn = -fkn;
  } else {
    const double base = attached_stiffness(ctx, node.id, n0);
    if (!(base > 0.0))
      throw fail(
          fmt::format("FKN > 0 is a factor on the stiffness at node {}, and no element "
                      "with stiffness is attached: give a negative (absolute) FKN",
                      node.id));
    data.kn = fkn * base;
  }
  const double fkt = real.get(12) != 0.0 ? real.get(12) : 1.0;
  data.kt = fkt < 0.0 ? -fkt : fkt * data.kn;
  const auto mat = model.materials.find(record.mat);
  data.mu = mat == model.materials.end() ? 0.0 : mat->second.get("MU", 0.0);
  if (data.mu < 0.0) throw fail(fmt::format("MU of material {} is negative", record.mat));
  return std::make_unique<NodeToSurfaceContact>(record.id, node.id, node.x, std::move(target),
                                                reach, real.get(10), data);
}

const ElementRegistration kConta175{{.name = "CONTA175",
                                     .number = 175,
                                     .family = kFamily,
                                     .n_nodes = 1,
                                     .real_constants = RealConstantUse::Required,
                                     .vtk_cell = VtkCell::Vertex,
                                     .result_names = ContactPoint::names(),
                                     .result_sequences = {{"CONT", "STAT", "STAT"},
                                                          {"CONT", "PRES", "FN"},
                                                          {"CONT", "PENE", "PENE"},
                                                          {"CONT", "GAP", "GAP"},
                                                          {"CONT", "SFRIC", "FT"},
                                                          {"CONT", "SLIDE", "SLIDE"}},
                                     .has_status = true,
                                     .create = make_node_to_surface_contact}};

}  // namespace

}  // namespace impactfe
