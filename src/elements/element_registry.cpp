#include <fmt/format.h>

#include <algorithm>
#include <cctype>

#include "core/text.h"
#include "elements/element.h"

namespace impactfe {

void Element::damping(const ElementContext&, const Eigen::VectorXd&, Eigen::MatrixXd& C) const {
  C.setZero(n_dofs(), n_dofs());
}

void Element::frame_acceleration_load(const ElementContext& ctx, const Vec3& a,
                                      Eigen::VectorXd& f) const {
  Eigen::MatrixXd m;
  mass(ctx, m);
  Eigen::VectorXd ra = Eigen::VectorXd::Zero(n_dofs());
  for (int i = 0; i < n_dofs(); ++i) {
    const int d = static_cast<int>(dofs()[static_cast<std::size_t>(i)].dof);
    if (d < 3) ra(i) = a(d);
  }
  f = -(m * ra);
}

const std::vector<ElementTypeInfo>& element_type_table() {
  static const std::vector<ElementTypeInfo> table = {
      {"LINK1", 1, ElementKind::Spar2D, 2},
      {"LINK8", 8, ElementKind::Spar3D, 2},
      {"LINK180", 180, ElementKind::Spar3D, 2},
      {"COMBIN14", 14, ElementKind::SpringDamper, 2},
      {"MASS21", 21, ElementKind::PointMass, 1},
      {"COMBIN40", 40, ElementKind::CombinationGap, 2},
      {"SHELL63", 63, ElementKind::Shell4, 4},
      {"SHELL181", 181, ElementKind::Shell4, 4},
      {"SOLID45", 45, ElementKind::Brick8, 8},
      {"SOLID185", 185, ElementKind::Brick8, 8},
      {"MATRIX50", 50, ElementKind::Superelement, 0},
  };
  return table;
}

const ElementTypeInfo* find_element_type(const std::string& name_or_number) {
  const std::string key = to_upper(name_or_number);
  const auto& table = element_type_table();
  for (const auto& info : table) {
    if (key == info.name || key == std::to_string(info.number)) return &info;
  }
  return nullptr;
}

std::unique_ptr<Element> create_element(const ElementBuildContext& ctx,
                                        const ElementRecord& record) {
  const auto type_it = ctx.model.element_types.find(record.type);
  if (type_it == ctx.model.element_types.end())
    throw InputError(record.where, fmt::format("element {}: element type {} is not defined",
                                               record.id, record.type));
  switch (type_it->second.kind) {
    case ElementKind::Spar2D:
    case ElementKind::Spar3D:
      return make_spar(ctx, record);
    case ElementKind::SpringDamper:
      return make_spring_damper(ctx, record);
    case ElementKind::PointMass:
      return make_point_mass(ctx, record);
    case ElementKind::CombinationGap:
      return make_combination_gap(ctx, record);
    case ElementKind::Shell4:
      return make_shell4(ctx, record);
    case ElementKind::Brick8:
      return make_brick8(ctx, record);
    case ElementKind::Superelement:
      return make_superelement(ctx, record);
  }
  throw InputError(record.where, "unknown element kind");
}

}  // namespace impactfe
