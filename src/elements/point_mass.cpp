#include "elements/point_mass.h"

#include <fmt/format.h>

#include "core/log.h"
#include "elements/element_registry.h"
#include "elements/line_element_data.h"

namespace impactfe {

PointMass::PointMass(int id, std::vector<DofKey> dofs, Eigen::VectorXd diagonal)
    : Element(id), dofs_(std::move(dofs)), diagonal_(std::move(diagonal)) {}

void PointMass::tangent(const ElementContext&, const Eigen::VectorXd&, Eigen::MatrixXd& K,
                        Eigen::VectorXd& f_int) const {
  K.setZero(n_dofs(), n_dofs());
  f_int.setZero(n_dofs());
}

void PointMass::mass(const ElementContext&, Eigen::MatrixXd& M) const {
  M = diagonal_.asDiagonal();
}

namespace {
/// KENE: the kinetic energy ½ vᵀ M v of the mass (MAPDL's element energy item, ETABLE,,KENE).
const std::vector<std::string> kPointMassResults = {"KENE"};
}  // namespace

const std::vector<std::string>& PointMass::result_names() const {
  return kPointMassResults;
}

void PointMass::results(const ElementContext&, const Eigen::VectorXd&, const Eigen::VectorXd& v,
                        ElementResultValues& out) const {
  out.assign(1, 0.5 * v.dot(diagonal_.cwiseProduct(v)));
}

namespace {

std::unique_ptr<Element> make_point_mass(const ElementBuildContext& ctx,
                                         const ElementRecord& record) {
  const Model& model = ctx.model;
  constexpr const char* family = "PointMass";
  const ElementType& type = line_data::element_type(model, record);
  const Node& node = line_data::node(model, record, 0, 1, family);
  const RealSet& real = line_data::real_set(model, record, family);
  if (record.nodes.size() > 1 && record.nodes[1] != 0 && record.nodes[1] != node.id)
    Log::warn("element {} ({}): only node I ({}) is used, node {} ignored", record.id, family,
              node.id, record.nodes[1]);

  std::vector<Dof> dofs;
  std::vector<double> values;
  switch (type.key(3)) {
    case 0:  // MASSX, MASSY, MASSZ, IXX, IYY, IZZ
      dofs = {Dof::UX, Dof::UY, Dof::UZ, Dof::ROTX, Dof::ROTY, Dof::ROTZ};
      for (int i = 1; i <= 6; ++i) values.push_back(real.get(i));
      break;
    case 2:  // MASS
      dofs = {Dof::UX, Dof::UY, Dof::UZ};
      values.assign(3, real.get(1));
      break;
    case 3:  // MASS, IZZ
      dofs = {Dof::UX, Dof::UY, Dof::ROTZ};
      values = {real.get(1), real.get(1), real.get(2)};
      break;
    case 4:  // MASS
      dofs = {Dof::UX, Dof::UY};
      values.assign(2, real.get(1));
      break;
    default:
      throw InputError(record.where,
                       fmt::format("element {} ({}): KEYOPT(3) = {} is not supported (0, 2, 3, 4)",
                                   record.id, family, type.key(3)));
  }
  Eigen::VectorXd diagonal(static_cast<Eigen::Index>(values.size()));
  for (std::size_t i = 0; i < values.size(); ++i) {
    if (values[i] < 0.0)
      throw InputError(record.where,
                       fmt::format("element {} ({}): negative mass or inertia {} (real set {})",
                                   record.id, family, values[i], record.real));
    diagonal(static_cast<Eigen::Index>(i)) = values[i];
  }
  if (diagonal.size() > 0 && diagonal.maxCoeff() == 0.0)
    throw InputError(record.where, fmt::format("element {} ({}): real set {} gives no mass (all "
                                               "masses and inertias are zero)",
                                               record.id, family, record.real));
  // The diagonal acts in global axes: in the axes of a rotated node (KEYOPT(2) = 1) only when
  // it is the same in every direction (a single MASS), so anything else is refused.
  if (type.key(2) == 1 && node.rotated() && type.key(3) == 0)
    throw InputError(record.where,
                     fmt::format("element {} ({}): KEYOPT(2) = 1 (masses and inertias in the "
                                 "nodal axes of rotated node {}) is not supported: give them in "
                                 "global axes (KEYOPT(2) = 0) or use KEYOPT(3) = 2 (one MASS)",
                                 record.id, family, node.id));
  std::vector<DofKey> keys;
  for (Dof d : dofs) keys.push_back(DofKey{node.id, d});
  return std::make_unique<PointMass>(record.id, std::move(keys), std::move(diagonal));
}

const ElementRegistration kMass21{{.name = "MASS21",
                                   .number = 21,
                                   .family = "PointMass",
                                   .n_nodes = 1,
                                   .real_constants = RealConstantUse::Required,
                                   .vtk_cell = VtkCell::Vertex,
                                   .role = ShapeRole::Point,
                                   .result_names = kPointMassResults,
                                   .create = make_point_mass}};

}  // namespace

}  // namespace impactfe
