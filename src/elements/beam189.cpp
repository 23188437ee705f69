// BEAM189, the 3-node quadratic beam (elements/beam189.h), and its registration.
#include "elements/beam189.h"

#include <fmt/format.h>

#include <Eigen/Geometry>

#include <array>
#include <cmath>
#include <stdexcept>
#include <utility>

#include "core/errors.h"
#include "elements/beam_setup.h"
#include "elements/element_registry.h"
#include "elements/line_element_data.h"
#include "materials/j2_plasticity.h"
#include "materials/linear_elastic.h"

namespace impactfe {

namespace {

using Mat3 = Eigen::Matrix3d;

/// Quadratic Lagrange functions of I (ξ = −1), J (+1), K (0) and their ξ-derivatives.
Eigen::Vector3d shape(double xi) {
  return {0.5 * xi * (xi - 1.0), 0.5 * xi * (xi + 1.0), 1.0 - xi * xi};
}
Eigen::Vector3d shape_derivative(double xi) {
  return {xi - 0.5, xi + 0.5, -2.0 * xi};
}

const double kGauss2 = 1.0 / std::sqrt(3.0);
/// 3-point Gauss rule (points, weights): exact for N_a N_b |x_ξ| of a straight element.
const std::array<std::pair<double, double>, 3> kGauss3{
    {{-std::sqrt(0.6), 5.0 / 9.0}, {0.0, 8.0 / 9.0}, {std::sqrt(0.6), 5.0 / 9.0}}};

}  // namespace

QuadraticBeam::QuadraticBeam(int id, QuadraticBeamData data) : Element(id), data_(std::move(data)) {
  for (int a = 0; a < 3; ++a)
    for (int c = 0; c < 6; ++c)
      dofs_.push_back(DofKey{data_.nodes[static_cast<std::size_t>(a)], static_cast<Dof>(c)});
  // x_ξ is linear in ξ: its component along the chord is positive on the whole element when it
  // is at both ends (the midside node lies in the middle half of I-J along the chord).
  const Vec3 chord = data_.x[1] - data_.x[0];
  for (double xi : {-1.0, 1.0}) {
    const Eigen::Vector3d dN = shape_derivative(xi);
    const Vec3 g = dN(0) * data_.x[0] + dN(1) * data_.x[1] + dN(2) * data_.x[2];
    if (!(g.dot(chord) > 1e-6 * chord.squaredNorm()))
      throw std::invalid_argument(
          "the midside node K is not in the middle half of I-J (the element folds back on "
          "itself)");
  }
  for (double xi : {-1.0, 0.0, 1.0}) axes_at(xi);  // throws for an element turning 90 degrees
  for (const auto& [xi, w] : kGauss3) {
    const Eigen::Vector3d dN = shape_derivative(xi);
    length_ += w * (dN(0) * data_.x[0] + dN(1) * data_.x[1] + dN(2) * data_.x[2]).norm();
  }
  const BeamSectionProperties& p = data_.section;
  const double E = data_.youngs_modulus, G = data_.shear_modulus;
  Eigen::Vector3d s;
  Mat3 Dab;
  integrate_fibres(
      p.fibres, Eigen::Vector3d::Zero(),
      [E](int, double, double& stress, double& tangent) {
        stress = 0.0;
        tangent = E;
      },
      s, Dab);
  D_.topLeftCorner<3, 3>() = Dab;
  D_(3, 3) = G * p.torsion;
  // Shear-rigid direction (no shear area): a penalty 1e5 × 12 EI/ℓ² (see the header).
  const double l2 = length_ * length_;
  D_(4, 4) = p.shear_area_y > 0.0 ? G * p.shear_area_y : 1e5 * 12.0 * Dab(2, 2) / l2;
  D_(5, 5) = p.shear_area_z > 0.0 ? G * p.shear_area_z : 1e5 * 12.0 * Dab(1, 1) / l2;
  for (double xi : {-kGauss2, kGauss2}) {
    double j = 0.0;
    const StrainMatrix B = strain_matrix(xi, &j);
    K_ += j * B.transpose() * D_ * B;  // Gauss weight 1
  }
  K_ = (0.5 * (K_ + K_.transpose())).eval();
}

Eigen::Matrix3d QuadraticBeam::axes_at(double xi) const {
  const Eigen::Vector3d dN = shape_derivative(xi);
  const Vec3 t = (dN(0) * data_.x[0] + dN(1) * data_.x[1] + dN(2) * data_.x[2]).normalized();
  const Vec3& z = data_.z_reference;
  Vec3 e3 = z - z.dot(t) * t;
  if (!(e3.norm() > 1e-3))
    throw std::invalid_argument(
        "the element's axis turns by 90 degrees or more from its chord toward the element z "
        "axis; use more elements along the curve");
  e3.normalize();
  Mat3 R;
  R.col(0) = t;
  R.col(1) = e3.cross(t);
  R.col(2) = e3;
  return R;
}

QuadraticBeam::StrainMatrix QuadraticBeam::strain_matrix(double xi, double* jacobian) const {
  const Eigen::Vector3d N = shape(xi), dN = shape_derivative(xi);
  const Vec3 g = dN(0) * data_.x[0] + dN(1) * data_.x[1] + dN(2) * data_.x[2];
  const double J = g.norm();
  const Mat3 R = axes_at(xi);
  const Vec3 t = R.col(0), e2 = R.col(1), e3 = R.col(2);
  StrainMatrix B = StrainMatrix::Zero();
  for (int a = 0; a < 3; ++a) {
    const double d = dN(a) / J;  // dN_a/ds
    const int u = 6 * a, r = 6 * a + 3;
    B.block<1, 3>(0, u) = d * t.transpose();   // ε0 = t·u'
    B.block<1, 3>(1, r) = d * e2.transpose();  // κy = e2·θ'
    B.block<1, 3>(2, r) = d * e3.transpose();  // κz = e3·θ'
    B.block<1, 3>(3, r) = d * t.transpose();   // twist = t·θ'
    B.block<1, 3>(4, u) = d * e2.transpose();  // γy = e2·u' − e3·θ
    B.block<1, 3>(4, r) = -N(a) * e3.transpose();
    B.block<1, 3>(5, u) = d * e3.transpose();  // γz = e3·u' + e2·θ
    B.block<1, 3>(5, r) = N(a) * e2.transpose();
  }
  if (jacobian) *jacobian = J;
  return B;
}

bool QuadraticBeam::is_nonlinear(const ElementContext& ctx) const {
  return ctx.large_deflection || ctx.stress_stiffening;
}

void QuadraticBeam::evaluate(const Vec18& u, bool stiffening, bool thermal, Vec18* f, Mat18* K,
                             Vec6* sg) const {
  using Vec6 = Eigen::Matrix<double, 6, 1>;
  if (f) f->setZero();
  if (K) K->setZero();
  for (int g = 0; g < 2; ++g) {
    const double xi = g == 0 ? -kGauss2 : kGauss2;
    double J = 0.0;
    StrainMatrix B = strain_matrix(xi, &J);
    Vec6 e = B * u;
    if (thermal) e(0) -= thermal_strain(xi);
    Eigen::Matrix<double, 3, 18> G = Eigen::Matrix<double, 3, 18>::Zero();
    Mat3 P = Mat3::Zero();
    if (stiffening) {
      // Moderate-rotation axial strain ε0 += ½ u'ᵀ (I − t tᵀ) u' (the transverse part of the
      // axis derivative; BEAM188's (Δv² + Δw²)/(2L²), Cook et al. §18.3): B's first row gains
      // ((I − t tᵀ) u')ᵀ G, and K the geometric term N Gᵀ (I − t tᵀ) G.
      const Eigen::Vector3d dN = shape_derivative(xi);
      for (int a = 0; a < 3; ++a) G.block<3, 3>(0, 6 * a) = dN(a) / J * Mat3::Identity();
      const Vec3 t = axes_at(xi).col(0);
      P = Mat3::Identity() - t * t.transpose();
      const Vec3 du = G * u;
      e(0) += 0.5 * du.dot(P * du);
      B.row(0) += (P * du).transpose() * G;
    }
    const Vec6 s = D_ * e;
    if (sg) sg[g] = s;
    if (f) *f += J * B.transpose() * s;  // Gauss weight 1
    if (K) *K += J * (B.transpose() * D_ * B + s(0) * G.transpose() * P * G);
  }
  if (K) *K = (0.5 * (*K + K->transpose())).eval();
}

void QuadraticBeam::tangent(const ElementContext& ctx, const Eigen::VectorXd& u, Eigen::MatrixXd& K,
                            Eigen::VectorXd& f_int) const {
  // Refused rather than computed without: the analysis would be wrong, not approximate.
  if (ctx.large_deflection)
    throw NotImplementedError(fmt::format(
        "element {} (BEAM189): large deflection (NLGEOM,ON) is not implemented for BEAM189 "
        "(BEAM188 has it)",
        id()));
  if (!ctx.stress_stiffening) {
    K = K_;
    f_int = K_ * u;
    return;
  }
  Vec18 f;
  Mat18 Kt;
  evaluate(u, true, false, &f, &Kt, nullptr);
  K = Kt;
  f_int = f;
}

void QuadraticBeam::mass(const ElementContext& ctx, Eigen::MatrixXd& M) const {
  const BeamSectionProperties& p = data_.section;
  const double rho = data_.density;
  const Eigen::Vector3d rotary(rho * (p.iyy + p.izz), rho * p.iyy, rho * p.izz);
  Mat18 Me = Mat18::Zero();
  for (const auto& [xi, w] : kGauss3) {
    const Eigen::Vector3d N = shape(xi), dN = shape_derivative(xi);
    const double J = (dN(0) * data_.x[0] + dN(1) * data_.x[1] + dN(2) * data_.x[2]).norm();
    const Mat3 R = axes_at(xi);
    const Mat3 Ir = R * rotary.asDiagonal() * R.transpose();
    for (int a = 0; a < 3; ++a)
      for (int b = 0; b < 3; ++b) {
        const double nn = w * J * N(a) * N(b);
        Me.block<3, 3>(6 * a, 6 * b) += nn * (rho * p.area + p.added_mass) * Mat3::Identity();
        Me.block<3, 3>(6 * a + 3, 6 * b + 3) += nn * Ir;
      }
  }
  if (ctx.lumped_mass) {
    // Row sums of each node's translational and rotational blocks.
    Mat18 L = Mat18::Zero();
    for (int a = 0; a < 3; ++a)
      for (int b = 0; b < 3; ++b)
        for (int o : {0, 3})
          L.block<3, 3>(6 * a + o, 6 * a + o) += Me.block<3, 3>(6 * a + o, 6 * b + o);
    Me = L;
  }
  M = (0.5 * (Me + Me.transpose())).eval();
}

double QuadraticBeam::thermal_strain(double xi) const {
  const std::vector<double>& dT = temperature_change();
  if (dT.size() < 3) return 0.0;
  const Eigen::Vector3d N = shape(xi);
  return thermal_expansion().alpha.x() * (N(0) * dT[0] + N(1) * dT[1] + N(2) * dT[2]);
}

QuadraticBeam::Vec18 QuadraticBeam::thermal_forces() const {
  Vec18 f = Vec18::Zero();
  for (double xi : {-kGauss2, kGauss2}) {
    double j = 0.0;
    const StrainMatrix B = strain_matrix(xi, &j);
    f += j * B.transpose() * D_.col(0) * thermal_strain(xi);  // D (ε_th, 0, ...)
  }
  return f;
}

void QuadraticBeam::thermal_load(const ElementContext&, Eigen::VectorXd& f) const {
  f = thermal_forces();
}

void QuadraticBeam::pressure_load(const ElementContext&, int face, const std::array<double, 4>& p,
                                  const Eigen::VectorXd&, Eigen::VectorXd& f) const {
  // BEAM189's faces (SFBEAM, SFE): 1 −z, 2 −y (normal), 3 +x (tangential) along the axis, the
  // force per length p[0] at I and p[1] at J, linear in ξ; 4 +x at I, 5 −x at J (axial).
  // ∫ N_a q(ξ) e(ξ) |x_ξ| dξ by 3-point Gauss (exact on a straight element), e the section axis
  // at the point, so the load follows a curved element's axis.
  Vec18 fe = Vec18::Zero();
  if (face >= 1 && face <= 3) {
    const int axis = face == 1 ? 2 : face == 2 ? 1 : 0;
    const double sign = face == 3 ? 1.0 : -1.0;
    for (const auto& [xi, w] : kGauss3) {
      const Eigen::Vector3d N = shape(xi), dN = shape_derivative(xi);
      const double jac = (dN(0) * data_.x[0] + dN(1) * data_.x[1] + dN(2) * data_.x[2]).norm();
      const double q = 0.5 * (1.0 - xi) * p[0] + 0.5 * (1.0 + xi) * p[1];
      const Vec3 load = sign * q * jac * w * axes_at(xi).col(axis);
      for (int a = 0; a < 3; ++a) fe.segment<3>(6 * a) += N(a) * load;
    }
  } else if (face == 4 || face == 5) {
    const int node = face - 4;  // I (ξ = −1) or J (+1)
    fe.segment<3>(6 * node) =
        (face == 4 ? 1.0 : -1.0) * p[0] * axes_at(node == 0 ? -1.0 : 1.0).col(0);
  } else {
    throw ModelError(fmt::format("element {} (BEAM189) has no face {}", id(), face));
  }
  f = fe;
}

const std::vector<std::string>& quadratic_beam_result_names() {
  static const std::vector<std::string> names = {
      "FX_I",   "MY_I",   "MZ_I",   "TQ_I",   "SFZ_I",  "SFY_I",  "FX_J",   "MY_J",
      "MZ_J",   "TQ_J",   "SFZ_J",  "SFY_J",  "SDIR_I", "SBYT_I", "SBYB_I", "SBZT_I",
      "SBZB_I", "SDIR_J", "SBYT_J", "SBYB_J", "SBZT_J", "SBZB_J", "SMAX_I", "SMIN_I",
      "SMAX_J", "SMIN_J", "FX_K",   "MY_K",   "MZ_K",   "TQ_K",   "SFZ_K",  "SFY_K"};
  return names;
}

const std::vector<std::string>& QuadraticBeam::result_names() const {
  return quadratic_beam_result_names();
}

void QuadraticBeam::results(const ElementContext& ctx, const Eigen::VectorXd& u,
                            const Eigen::VectorXd&, ElementResultValues& out) const {
  using Vec6 = Eigen::Matrix<double, 6, 1>;
  out.assign(quadratic_beam_result_names().size(), 0.0);
  // Generalised stresses (N, My, Mz, T, Vy, Vz) = D (B u − ε_th) at the two Gauss points (with
  // the moderate-rotation axial strain under stress stiffening), and the linear field through
  // them at ξ: exact wherever the resultants are linear along the element (end loads, a thermal
  // strain), also on a curved element.
  Vec6 sg[2];
  evaluate(u, ctx.stress_stiffening && !ctx.large_deflection, true, nullptr, nullptr, sg);
  auto at = [&](double xi) -> Vec6 {
    return 0.5 * (sg[0] + sg[1]) + 0.5 * std::sqrt(3.0) * xi * (sg[1] - sg[0]);
  };
  // Stored order FX MY MZ TQ SFZ SFY.
  auto store = [&](std::size_t o, const Vec6& s) {
    out[o + 0] = s(0), out[o + 1] = s(1), out[o + 2] = s(2), out[o + 3] = s(3), out[o + 4] = s(5),
            out[o + 5] = s(4);
  };
  for (int end = 0; end < 2; ++end) {
    const Vec6 s = at(end == 0 ? -1.0 : 1.0);
    store(6 * static_cast<std::size_t>(end), s);
    const BeamFibreStresses st = beam_fibre_stresses(data_.section, data_.youngs_modulus,
                                                     D_.topLeftCorner<3, 3>(), s(0), s(1), s(2));
    const std::size_t so = 12 + 5 * static_cast<std::size_t>(end);
    out[so + 0] = st.sdir, out[so + 1] = st.sbyt, out[so + 2] = st.sbyb, out[so + 3] = st.sbzt,
             out[so + 4] = st.sbzb;
    out[22 + 2 * static_cast<std::size_t>(end)] = st.smax;
    out[23 + 2 * static_cast<std::size_t>(end)] = st.smin;
  }
  store(26, at(0.0));
}

namespace {

std::unique_ptr<Element> make_beam189(const ElementBuildContext& ctx, const ElementRecord& record) {
  const Model& model = ctx.model;
  const char* name = "BEAM189";
  const ElementType& type = line_data::element_type(model, record);
  if (type.key(1) != 0)
    throw beam_element_error(record, name, "KEYOPT(1) = 1 (warping DOF) is not supported");
  if (ctx.large_deflection)
    throw beam_element_error(
        record, name,
        "large deflection (NLGEOM,ON) is not implemented for BEAM189 (BEAM188 has it)");
  if (record.nodes.size() < 3 || record.nodes[2] <= 0)
    throw beam_element_error(record, name, "needs its midside node K (E,I,J,K[,L])");
  QuadraticBeamData d;
  for (std::size_t a = 0; a < 3; ++a) {
    const Node& n = line_data::node(model, record, a, 3, name);
    d.nodes[a] = n.id;
    d.x[a] = n.x;
  }
  if (d.nodes[0] == d.nodes[1] || d.nodes[2] == d.nodes[0] || d.nodes[2] == d.nodes[1])
    throw beam_element_error(record, name,
                             fmt::format("nodes I, J, K must be three different nodes ({}, {}, {})",
                                         d.nodes[0], d.nodes[1], d.nodes[2]));
  if (!((d.x[1] - d.x[0]).norm() > 0.0))
    throw beam_element_error(
        record, name,
        fmt::format("zero length (nodes {} and {} coincide)", d.nodes[0], d.nodes[1]));
  const Vec3* xl = nullptr;
  if (record.nodes.size() > 3 && record.nodes[3] > 0)
    xl = &line_data::node(model, record, 3, 4, name).x;
  d.z_reference = beam_frame(record, name, d.x[0], d.x[1], xl, 0.0).col(2);
  const ElasticMaterial mat = elastic_material(model, record, name);
  d.youngs_modulus = mat.youngs_modulus;
  d.shear_modulus = mat.youngs_modulus / (2.0 * (1.0 + mat.poisson_ratio));
  d.density = mat.density;
  d.section = record_beam_section(model, record, name, mat.poisson_ratio, d.shear_modulus);
  if (plasticity_of(model, record, d.youngs_modulus, mat.poisson_ratio))
    throw beam_element_error(
        record, name,
        fmt::format("material {} has a TB plasticity table: plasticity is not implemented for "
                    "BEAM189 (BEAM188 has it)",
                    record.mat));
  try {
    return std::make_unique<QuadraticBeam>(record.id, std::move(d));
  } catch (const std::invalid_argument& e) {
    throw beam_element_error(record, name, e.what());
  }
}

std::vector<ResultSequence> beam189_sequences() {
  // The SMISC numbers of BEAM188 (APDL_MODELING §8.1): 1-6 / 14-19 FX MY MZ TQ SFZ SFY at I / J,
  // 31-35 / 36-40 SDIR SByT SByB SBzT SBzB at I / J.
  std::vector<ResultSequence> all;
  for (auto part :
       {numbered_sequences("SMISC", 1, {"FX_I", "MY_I", "MZ_I", "TQ_I", "SFZ_I", "SFY_I"}),
        numbered_sequences("SMISC", 14, {"FX_J", "MY_J", "MZ_J", "TQ_J", "SFZ_J", "SFY_J"}),
        numbered_sequences("SMISC", 31,
                           {"SDIR_I", "SBYT_I", "SBYB_I", "SBZT_I", "SBZB_I", "SDIR_J", "SBYT_J",
                            "SBYB_J", "SBZT_J", "SBZB_J"})})
    all.insert(all.end(), part.begin(), part.end());
  return all;
}

const ElementRegistration kBeam189{
    {.name = "BEAM189",
     .number = 189,
     .family = "QuadraticBeam",
     .n_nodes = 3,
     .n_optional_nodes = 1,
     .real_constants = RealConstantUse::None,
     .needs_material = true,
     .section_types = {"BEAM"},
     .vtk_cell = VtkCell::QuadraticEdge,
     .role = ShapeRole::Line,
     .result_names = quadratic_beam_result_names(),
     .result_sequences = beam189_sequences(),
     .faces = {{0, 1}, {0, 1}, {0, 1}, {0}, {1}},  // SFBEAM / SFE faces of BEAM188
     .note = "BEAM189: quadratic Timoshenko beam, 2-point Gauss along the axis; linear elastic, "
             "small deflection with stress stiffening (NLGEOM and plasticity refused)",
     .create = make_beam189}};

}  // namespace

}  // namespace impactfe
