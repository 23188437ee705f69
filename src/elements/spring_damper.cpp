#include "elements/spring_damper.h"

#include <fmt/format.h>

#include <cmath>

#include "core/log.h"
#include "elements/element_registry.h"
#include "elements/line_element_data.h"

namespace impactfe {

using corotational::AxialKinematics;
using corotational::AxialMember;

SpringDamper::SpringDamper(int id, SpringMode mode, std::vector<DofKey> dofs, AxialMember member,
                           double stiffness, double damping)
    : Element(id),
      mode_(mode),
      dofs_(std::move(dofs)),
      member_(std::move(member)),
      stiffness_(stiffness),
      damping_(damping) {}

AxialKinematics SpringDamper::kinematics(const ElementContext& ctx) const {
  // Torsional and scalar springs have no geometry to update: always linear.
  if (!longitudinal()) return AxialKinematics::Linear;
  if (ctx.large_deflection) return AxialKinematics::Corotational;
  if (ctx.stress_stiffening) return AxialKinematics::StressStiffened;
  return AxialKinematics::Linear;
}

bool SpringDamper::is_nonlinear(const ElementContext& ctx) const {
  return kinematics(ctx) != AxialKinematics::Linear;
}

void SpringDamper::tangent(const ElementContext& ctx, const Eigen::VectorXd& u, Eigen::MatrixXd& K,
                           Eigen::VectorXd& f_int) const {
  corotational::axial_response(member_, kinematics(ctx), stiffness_, 0.0, u, K, f_int, id());
}

void SpringDamper::mass(const ElementContext&, Eigen::MatrixXd& M) const {
  M.setZero(n_dofs(), n_dofs());
}

void SpringDamper::damping(const ElementContext& ctx, const Eigen::VectorXd& u,
                           Eigen::MatrixXd& C) const {
  const int d = member_.dim();
  C.setZero(2 * d, 2 * d);
  Eigen::VectorXd n = member_.n;
  if (kinematics(ctx) == AxialKinematics::Corotational) {
    const Eigen::VectorXd chord = member_.length * member_.n + u.tail(d) - u.head(d);
    if (chord.norm() > 0.0) n = chord.normalized();
  }
  corotational::add_block(n * n.transpose(), damping_, C);
}

namespace {
// SENE: the strain energy of the linear spring, k e² / 2 (also under large rotation: the
// spring is linear in its stretch e).
const std::vector<std::string> kSpringDamperResults = {"FORC", "STRETCH", "SENE"};
}  // namespace

const std::vector<std::string>& SpringDamper::result_names() const {
  return kSpringDamperResults;
}

void SpringDamper::results(const ElementContext& ctx, const Eigen::VectorXd& u,
                           const Eigen::VectorXd&, ElementResultValues& out) const {
  Eigen::MatrixXd K;
  Eigen::VectorXd f;
  const auto s =
      corotational::axial_response(member_, kinematics(ctx), stiffness_, 0.0, u, K, f, id());
  out = {s.force, s.extension, 0.5 * stiffness_ * s.extension * s.extension};
}

namespace {

std::unique_ptr<Element> make_spring_damper(const ElementBuildContext& ctx,
                                            const ElementRecord& record) {
  const Model& model = ctx.model;
  constexpr const char* family = "SpringDamper";
  const ElementType& type = line_data::element_type(model, record);
  const auto [ni, nj] = line_data::distinct_node_pair(model, record, family);
  const int k2 = type.key(2);
  const int k3 = type.key(3);
  SpringMode mode;
  if (k2 == 0) {
    if (k3 == 0) {
      mode = SpringMode::Longitudinal3D;
    } else if (k3 == 1) {
      mode = SpringMode::Torsional3D;
    } else if (k3 == 2) {
      mode = SpringMode::Longitudinal2D;
    } else {
      throw InputError(record.where,
                       fmt::format("element {} ({}): KEYOPT(3) = {} is not supported (0, 1, 2)",
                                   record.id, family, k3));
    }
  } else if (k2 >= 1 && k2 <= 6) {
    mode = SpringMode::Scalar;
  } else {
    throw InputError(record.where,
                     fmt::format("element {} ({}): KEYOPT(2) = {} is not supported (0..6)",
                                 record.id, family, k2));
  }

  const RealSet& real = line_data::real_set(model, record, family);
  const double stiffness = real.get(1);
  const double damping = real.get(2);
  if (stiffness < 0.0 || damping < 0.0)
    throw InputError(record.where,
                     fmt::format("element {} ({}): stiffness K = {:g} and damping CV1 = {:g} must "
                                 "not be negative (real set {})",
                                 record.id, family, stiffness, damping, record.real));
  // An empty set (R,1,) would give an element that does nothing: its nodes would silently lose
  // their only connection.
  if (stiffness == 0.0 && damping == 0.0)
    throw InputError(record.where,
                     fmt::format("element {} ({}): real set {} gives neither a stiffness K nor a "
                                 "damping CV1 (R,{},K,CV1)",
                                 record.id, family, record.real, record.real));
  // CV2 (nonlinear damping) is refused before (element_fields.cpp).

  AxialMember member;
  std::vector<DofKey> dofs;
  if (mode == SpringMode::Scalar) {
    // One DOF per node: works like a scalar spring, node positions are irrelevant.
    member.n = Eigen::VectorXd::Ones(1);
    member.length = 0.0;
    const Dof dof = static_cast<Dof>(k2 - 1);
    dofs = {DofKey{ni.id, dof}, DofKey{nj.id, dof}};
  } else {
    const Vec3 chord = nj.x - ni.x;
    const double length = chord.norm();
    if (!(length > 0.0))
      throw InputError(record.where,
                       fmt::format("element {} ({}): nodes {} and {} coincide (zero length); "
                                   "use KEYOPT(2) = 1..6 for a 1-D spring",
                                   record.id, family, ni.id, nj.id));
    const bool planar = mode == SpringMode::Longitudinal2D;
    if (planar && std::abs(chord.z()) > 1e-9 * length)
      throw InputError(record.where,
                       fmt::format("element {} ({}): a 2-D spring (KEYOPT(3) = 2) must lie in "
                                   "an X-Y plane",
                                   record.id, family));
    const int d = planar ? 2 : 3;
    member.n = (chord / length).head(d);
    member.length = length;
    const int first = mode == SpringMode::Torsional3D ? 3 : 0;
    for (int node : {ni.id, nj.id})
      for (int c = 0; c < d; ++c) dofs.push_back(DofKey{node, static_cast<Dof>(first + c)});
  }
  return std::make_unique<SpringDamper>(record.id, mode, std::move(dofs), std::move(member),
                                        stiffness, damping);
}

const ElementRegistration kCombin14{
    {.name = "COMBIN14",
     .number = 14,
     .family = "SpringDamper",
     .n_nodes = 2,
     .real_constants = RealConstantUse::Required,
     .vtk_cell = VtkCell::Line,
     .role = ShapeRole::Line,
     .result_names = kSpringDamperResults,
     .result_sequences = {{"SMISC", "1", "FORC"}, {"NMISC", "1", "STRETCH"}},
     .create = make_spring_damper}};

}  // namespace

}  // namespace impactfe
