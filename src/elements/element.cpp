#include "elements/element.h"

#include <fmt/format.h>

#include <algorithm>
#include <cmath>

#include "elements/element_fields.h"
#include "elements/element_registry.h"

namespace impactfe {

std::unique_ptr<Element> create_element(const ElementBuildContext& ctx,
                                        const ElementRecord& record) {
  const auto type_it = ctx.model.element_types.find(record.type);
  if (type_it == ctx.model.element_types.end())
    throw InputError(record.where, fmt::format("element {}: element type {} is not defined",
                                               record.id, record.type));
  const ElementType& type = type_it->second;
  const ElementTypeDescriptor& descriptor = element_type_descriptor(type);
  if (const std::string why = esys_refusal(ctx.model, record); !why.empty())
    throw InputError(record.where, fmt::format("element {}: {}", record.id, why));
  // The element's own checks first (they name the field in the element's words), then: every
  // KEYOPT and real constant given is one the element carries out (element_fields.h).
  auto element = descriptor.create(ctx, record);
  if (const std::string why = keyopt_refusal(type); !why.empty())
    throw InputError(type.where.known() ? type.where : record.where,
                     fmt::format("element type {}: {}", type.id, why));
  const auto section = ctx.model.sections.find(record.secnum);
  const bool by_section = record.secnum > 0 && section != ctx.model.sections.end() &&
                          descriptor.accepts_section(section->second.type) &&
                          !section->second.data.empty();
  const bool reads_real =
      descriptor.real_constants == RealConstantUse::Required ||
      descriptor.real_constants == RealConstantUse::Optional ||
      (descriptor.real_constants == RealConstantUse::UnlessSection && !by_section);
  if (const auto set = ctx.model.real_sets.find(record.real);
      reads_real && set != ctx.model.real_sets.end())
    if (const std::string why = real_set_refusal(type, set->second); !why.empty())
      throw InputError(record.where, fmt::format("element {}: {}", record.id, why));
  return element;
}

void Element::restore_history_state(const std::vector<double>& state) {
  IMPACTFE_CHECK(state.empty(),
                 fmt::format("element {}: a saved state of {} values for an element without one",
                             id(), state.size()));
}

void Element::internal_force(const ElementContext& ctx, const Eigen::VectorXd& u,
                             Eigen::VectorXd& f_int) const {
  Eigen::MatrixXd K;
  tangent(ctx, u, K, f_int);
}

void Element::damping(const ElementContext&, const Eigen::VectorXd&, Eigen::MatrixXd& C) const {
  C.setZero(n_dofs(), n_dofs());
}

void Element::frame_acceleration_load(const ElementContext& ctx, const Eigen::Matrix3Xd& a,
                                      Eigen::MatrixXd& f) const {
  Eigen::MatrixXd m;
  mass(ctx, m);
  Eigen::MatrixXd ra = Eigen::MatrixXd::Zero(n_dofs(), a.cols());
  for (int i = 0; i < n_dofs(); ++i) {
    const int d = static_cast<int>(dofs()[static_cast<std::size_t>(i)].dof);
    if (d < 3) ra.row(i) = a.row(d);
  }
  // Column by column: the matrix-vector product of a single load, whatever the count.
  f.resize(n_dofs(), a.cols());
  for (Eigen::Index k = 0; k < a.cols(); ++k) f.col(k).noalias() = -(m * ra.col(k));
}

void Element::acceleration_field_load(const ElementContext& ctx,
                                      const std::vector<LinearAccelerationField>& fields,
                                      const std::function<Vec3(int)>& position,
                                      Eigen::MatrixXd& f) const {
  const int n = n_dofs();
  const Eigen::Index n_fields = static_cast<Eigen::Index>(fields.size());
  f.setZero(n, n_fields);
  Eigen::MatrixXd m;
  mass(ctx, m);
  if (m.size() == 0 || (m.array() == 0.0).all()) return;  // no mass: no inertia load
  // The translations each node carries (bit d for U_d), for the check below.
  std::map<int, unsigned> translations;
  for (const DofKey& key : dofs()) {
    unsigned& bits = translations[key.node];
    if (static_cast<int>(key.dof) < 3) bits |= 1u << static_cast<int>(key.dof);
  }
  Eigen::MatrixXd nodal(n, n_fields);
  for (Eigen::Index k = 0; k < n_fields; ++k) {
    const LinearAccelerationField& field = fields[static_cast<std::size_t>(k)];
    std::map<int, Vec3> at_node;
    double largest = 0.0;
    for (const auto& [node, bits] : translations) {
      at_node[node] = field.at(position(node));
      largest = std::max(largest, at_node[node].cwiseAbs().maxCoeff());
    }
    for (const auto& [node, bits] : translations)
      for (int d = 0; d < 3; ++d)
        if (bits != 0 && (bits & (1u << d)) == 0 && std::abs(at_node[node](d)) > 1e-9 * largest)
          throw ModelError(fmt::format(
              "element {} ({}): the rotational inertia load accelerates node {} along {} "
              "({:g}), a direction in which the element has no DOF, so that part of the load "
              "could not act (a plane element takes accelerations in its X-Y plane only)",
              id(), family(), node, "XYZ"[d], at_node[node](d)));
    for (int i = 0; i < n; ++i) {
      const DofKey& key = dofs()[static_cast<std::size_t>(i)];
      const int d = static_cast<int>(key.dof);
      nodal(i, k) = d < 3 ? at_node[key.node](d) : d < 6 ? field.angular(d - 3) : 0.0;
    }
  }
  for (Eigen::Index k = 0; k < n_fields; ++k) f.col(k).noalias() = -(m * nodal.col(k));
}

void require_axisymmetric_fields(const Element& element,
                                 const std::vector<LinearAccelerationField>& fields) {
  // A quarter turn about Y, (x, y, z) -> (z, y, -x): a field unchanged by it (R G Rᵀ = G,
  // R a0 = a0, R α = α) is unchanged by every turn about Y, since its parts are linear.
  Mat3 turn;
  turn << 0.0, 0.0, 1.0, 0.0, 1.0, 0.0, -1.0, 0.0, 0.0;
  const auto differs = [](const auto& a, const auto& b) {
    return (a - b).cwiseAbs().maxCoeff() > 1e-12 * std::max(1.0, b.cwiseAbs().maxCoeff());
  };
  for (const LinearAccelerationField& field : fields)
    if (differs(Mat3(turn * field.gradient * turn.transpose()), field.gradient) ||
        differs(Vec3(turn * field.at_origin), field.at_origin) ||
        differs(Vec3(turn * field.angular), field.angular))
      throw ModelError(fmt::format(
          "element {} ({}) is axisymmetric about the global Y axis, and the rotational inertia "
          "load is not: only angular velocities and accelerations about Y (OMEGA, DOMEGA, "
          "CGOMGA, DCGOMG) with CGLOC on the Y axis keep the load axisymmetric",
          element.id(), element.family()));
}

void Element::pressure_load(const ElementContext&, int face, const std::array<double, 4>&,
                            const Eigen::VectorXd&, Eigen::VectorXd&) const {
  throw ModelError(fmt::format("element {} ({}) takes no surface loads (face {} pressure)", id(),
                               family(), face));
}

void Element::thermal_load(const ElementContext&, Eigen::VectorXd&) const {
  throw NotImplementedError(fmt::format(
      "element {} ({}): thermal strain (MP,ALPX with a temperature other than the reference "
      "temperature) is not implemented for this element type",
      id(), family()));
}

}  // namespace impactfe
