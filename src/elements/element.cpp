#include "elements/element.h"

#include <fmt/format.h>

#include "elements/element_registry.h"

namespace impactfe {

std::unique_ptr<Element> create_element(const ElementBuildContext& ctx,
                                        const ElementRecord& record) {
  const auto type_it = ctx.model.element_types.find(record.type);
  if (type_it == ctx.model.element_types.end())
    throw InputError(record.where, fmt::format("element {}: element type {} is not defined",
                                               record.id, record.type));
  return element_type_descriptor(type_it->second).create(ctx, record);
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

void Element::pressure_load(const ElementContext&, int face, const std::array<double, 4>&,
                            const Eigen::VectorXd&, Eigen::VectorXd&) const {
  throw ModelError(fmt::format("element {} ({}) takes no surface loads (face {} pressure)", id(),
                               family(), face));
}

}  // namespace impactfe
