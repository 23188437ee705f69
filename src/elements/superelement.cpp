#include "elements/superelement.h"

#include <fmt/format.h>

#include "core/log.h"
#include "elements/element_registry.h"

namespace impactfe {

namespace {
/// MAPDL's node-coincidence tolerance for master nodes of a use pass (TOLER, spec §10.6).
constexpr double kCoordinateTolerance = 1e-4;
}  // namespace

Superelement::Superelement(int id, std::string path, std::shared_ptr<const SuperelementData> data)
    : Element(id), path_(std::move(path)), data_(std::move(data)), dofs_(data_->master_keys()) {}

void Superelement::tangent(const ElementContext&, const Eigen::VectorXd& u, Eigen::MatrixXd& K,
                           Eigen::VectorXd& f_int) const {
  K = data_->stiffness;
  f_int = K * u;
}

void Superelement::mass(const ElementContext&, Eigen::MatrixXd& M) const {
  if (data_->mass)
    M = *data_->mass;
  else
    M.setZero(n_dofs(), n_dofs());
}

void Superelement::damping(const ElementContext&, const Eigen::VectorXd&,
                           Eigen::MatrixXd& C) const {
  if (data_->damping)
    C = *data_->damping;
  else
    C.setZero(n_dofs(), n_dofs());
}

void Superelement::frame_acceleration_load(const ElementContext&, const Eigen::Matrix3Xd& a,
                                           Eigen::MatrixXd& f) const {
  f.resize(data_->unit_acceleration.rows(), a.cols());
  for (Eigen::Index k = 0; k < a.cols(); ++k)
    f.col(k).noalias() = -(data_->unit_acceleration * a.col(k));
}

void Superelement::acceleration_field_load(const ElementContext&,
                                           const std::vector<LinearAccelerationField>&,
                                           const std::function<Vec3(int)>&,
                                           Eigen::MatrixXd&) const {
  // The reduced mass at the master nodes alone would miss the field over the interior: the
  // exact load needs the vectors of the generation pass, which the file does not have.
  throw NotImplementedError(
      fmt::format("superelement {}: rotational inertia loads (OMEGA, DOMEGA, CGOMGA, DCGOMG) on a "
                  "superelement are not implemented (its file has no load vectors for them)",
                  id()));
}

namespace {
const std::vector<std::string> kSuperelementResults;
}  // namespace

const std::vector<std::string>& Superelement::result_names() const {
  return kSuperelementResults;
}

void Superelement::results(const ElementContext&, const Eigen::VectorXd&, const Eigen::VectorXd&,
                           ElementResultValues& out) const {
  out.clear();
}

namespace {

std::unique_ptr<Element> make_superelement(const ElementBuildContext& ctx,
                                           const ElementRecord& record) {
  if (!ctx.resolve_superelement_file)
    throw InputError(record.where,
                     fmt::format("element {}: no superelement file resolver", record.id));
  const std::string path = ctx.resolve_superelement_file(record);
  auto data = std::make_shared<const SuperelementData>(read_superelement(path, record.where));
  if (data->masters.empty())
    throw InputError(
        record.where,
        fmt::format("element {}: superelement file {} has no master DOFs", record.id, path));
  // The master nodes of the use pass are the nodes with the masters' numbers.
  for (const SuperelementMaster& m : data->masters) {
    auto it = ctx.model.nodes.find(m.key.node);
    if (it == ctx.model.nodes.end())
      throw InputError(
          record.where,
          fmt::format("element {}: master node {} of superelement {} ({}) is not "
                      "defined in this model; define it with N at ({}, {}, {})",
                      record.id, m.key.node, data->name, path, m.x(0), m.x(1), m.x(2)));
    const double distance = (it->second.x - m.x).norm();
    if (distance > kCoordinateTolerance)
      Log::warn(
          "element {}: node {} is at ({}, {}, {}) but superelement {} has its master there at "
          "({}, {}, {}) (distance {:.3g} > {})",
          record.id, m.key.node, it->second.x(0), it->second.x(1), it->second.x(2), data->name,
          m.x(0), m.x(1), m.x(2), distance, kCoordinateTolerance);
    if ((it->second.angles_deg - m.angles_deg).norm() > kCoordinateTolerance)
      Log::warn("element {}: node {} nodal angles differ from the superelement's master node",
                record.id, m.key.node);
  }
  Log::info("element {}: superelement {} from {} ({} master DOFs, matrices {})", record.id,
            data->name, path, data->n_masters(), data->matrices);
  return std::make_unique<Superelement>(record.id, path, std::move(data));
}

const ElementRegistration kMatrix50{{.name = "MATRIX50",
                                     .number = 50,
                                     .family = "Superelement",
                                     .defined_by_file = true,
                                     .vtk_cell = VtkCell::PolyVertex,
                                     .role = ShapeRole::Superelement,
                                     .result_names = kSuperelementResults,
                                     .create = make_superelement}};

}  // namespace

}  // namespace impactfe
