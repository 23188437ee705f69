#include "elements/shell4.h"

#include <fmt/format.h>

#include <Eigen/Dense>
#include <Eigen/Geometry>

#include <algorithm>
#include <cmath>
#include <stdexcept>

#include "core/errors.h"
#include "core/log.h"
#include "elements/element_registry.h"

namespace impactfe {

namespace {

using Mat3 = Eigen::Matrix3d;
// Fixed-capacity types (at most 4 corners): the co-rotational kinematics runs dozens of times
// per element and iteration, so it must not touch the heap.
using Mat3N = Eigen::Matrix<double, 3, Eigen::Dynamic, Eigen::ColMajor, 3, 12>;
using RowN = Eigen::Matrix<double, 1, Eigen::Dynamic, Eigen::RowMajor, 1, 12>;
using Corners = Eigen::Matrix<double, 3, Eigen::Dynamic, Eigen::ColMajor, 3, 4>;

Mat3 spin(const Vec3& v) {
  Mat3 S;
  S << 0.0, -v.z(), v.y(), v.z(), 0.0, -v.x(), -v.y(), v.x(), 0.0;
  return S;
}

/// Rotation matrix of the rotation vector ψ (Rodrigues).
Mat3 exp_so3(const Vec3& psi) {
  const double t = psi.norm();
  const Mat3 S = spin(psi);
  double a, b;
  if (t < 1e-6) {
    a = 1.0 - t * t / 6.0;
    b = 0.5 - t * t / 24.0;
  } else {
    a = std::sin(t) / t;
    b = (1.0 - std::cos(t)) / (t * t);
  }
  return Mat3::Identity() + a * S + b * S * S;
}

/// Rotation vector of R, angle in [0, π] (via the quaternion, robust near 0 and π).
Vec3 log_so3(const Mat3& R) {
  Eigen::Quaterniond q(R);
  if (q.w() < 0.0) q.coeffs() *= -1.0;
  const Vec3 v = q.vec();
  const double s = v.norm();
  if (s < 1e-12) return 2.0 * v;
  return (2.0 * std::atan2(s, q.w()) / s) * v;
}

/// Left Jacobian T(ψ) of exp: δR Rᵀ = spin(T δψ).
Mat3 left_jacobian(const Vec3& psi) {
  const double t = psi.norm();
  const Mat3 S = spin(psi);
  double a, b;
  if (t < 1e-4) {
    a = 0.5 - t * t / 24.0;
    b = 1.0 / 6.0 - t * t / 120.0;
  } else {
    a = (1.0 - std::cos(t)) / (t * t);
    b = (t - std::sin(t)) / (t * t * t);
  }
  return Mat3::Identity() + a * S + b * S * S;
}

/// Inverse of the left Jacobian.
Mat3 left_jacobian_inverse(const Vec3& psi) {
  const double t = psi.norm();
  const Mat3 S = spin(psi);
  double c;
  if (t < 1e-4)
    c = 1.0 / 12.0 + t * t / 720.0;
  else
    c = 1.0 / (t * t) - (1.0 + std::cos(t)) / (2.0 * t * std::sin(t));
  return Mat3::Identity() - 0.5 * S + c * S * S;
}

/// Element frame of corner positions x: e3 along the facet normal ((K−I)×(L−J) for a quad,
/// i.e. the mean plane; (J−I)×(K−I) for a triangle), e1 along I→J projected on the plane,
/// e2 = e3×e1; c = centroid of the corners. If G != nullptr it receives the frame spin
/// δω = G δx (3 × 3n, global components) for corner translation variations δx.
void element_frame(const Corners& x, Mat3& R, Vec3& c, Mat3N* G) {
  const int n = static_cast<int>(x.cols());
  c = x.rowwise().mean();
  Vec3 a, b;
  int ia0, ia1, ib0, ib1;  // a = x[ia1] − x[ia0], b = x[ib1] − x[ib0]
  if (n == 4) {
    ia0 = 0, ia1 = 2, ib0 = 1, ib1 = 3;
  } else {
    ia0 = 0, ia1 = 1, ib0 = 0, ib1 = 2;
  }
  a = x.col(ia1) - x.col(ia0);
  b = x.col(ib1) - x.col(ib0);
  const Vec3 nvec = a.cross(b);
  const double nn = nvec.norm();
  const Vec3 e3 = nvec / nn;
  const Vec3 v = x.col(1) - x.col(0);
  const Vec3 p = v - v.dot(e3) * e3;
  const double pn = p.norm();
  const Vec3 e1 = p / pn;
  const Vec3 e2 = e3.cross(e1);
  R.col(0) = e1;
  R.col(1) = e2;
  R.col(2) = e3;
  if (G == nullptr) return;
  // d(a×b) = −spin(b) da + spin(a) db, with da, db selecting corner translations.
  Mat3N Dn = Mat3N::Zero(3, 3 * n);
  Dn.block<3, 3>(0, 3 * ia1) -= spin(b);
  Dn.block<3, 3>(0, 3 * ia0) += spin(b);
  Dn.block<3, 3>(0, 3 * ib1) += spin(a);
  Dn.block<3, 3>(0, 3 * ib0) -= spin(a);
  const Mat3N De3 = (Mat3::Identity() - e3 * e3.transpose()) / nn * Dn;
  const RowN w1 = -e2.transpose() * De3;
  const RowN w2 = e1.transpose() * De3;
  RowN dv = RowN::Zero(1, 3 * n);  // e2ᵀ d(x1 − x0)
  dv.segment<3>(3) += e2.transpose();
  dv.segment<3>(0) -= e2.transpose();
  const RowN w3 = (dv - v.dot(e3) * e2.transpose() * De3) / pn;
  *G = e1 * w1 + e2 * w2 + e3 * w3;
}

double von_mises(double sx, double sy, double sxy) {
  return std::sqrt(std::max(0.0, sx * sx - sx * sy + sy * sy + 3.0 * sxy * sxy));
}

}  // namespace

Shell4::Shell4(int id, const Shell4Data& data, const SourceLocation& where)
    : Element(id), n_(static_cast<int>(data.node_ids.size())), X_(data.positions) {
  for (int node : data.node_ids)
    for (Dof d : kAllDofs) dofs_.push_back(DofKey{node, d});
  Corners corners(3, n_);
  for (int a = 0; a < n_; ++a) corners.col(a) = X_[static_cast<std::size_t>(a)];
  element_frame(corners, R0_, c0_, nullptr);
  if (!R0_.allFinite())
    throw InputError(where,
                     fmt::format("element {}: zero area (coincident or collinear nodes)", id));
  std::vector<Eigen::Vector2d> xy;
  double hmax = 0.0;
  for (const auto& x : X_) {
    const Vec3 l = R0_.transpose() * (x - c0_);
    xy.emplace_back(l.x(), l.y());
    h_.push_back(l.z());
    hmax = std::max(hmax, std::abs(l.z()));
  }
  try {
    kernel_ = std::make_unique<shell::FlatShellKernel>(xy, data.kernel);
  } catch (const std::invalid_argument& e) {
    throw InputError(where, fmt::format("element {}: {}", id, e.what()));
  }
  const double warp = hmax / std::sqrt(kernel_->area());
  if (warp > 0.02)
    Log::warn(
        "element {}: warped quadrilateral (corner offset / sqrt(area) = {:.3g}), projected "
        "on its mean plane",
        id, warp);
  theta_ = data.theta_deg * M_PI / 180.0;

  const int nd = 6 * n_;
  W_.setIdentity(nd, nd);
  Eigen::MatrixXd T = Eigen::MatrixXd::Zero(nd, nd);
  for (int a = 0; a < n_; ++a) {
    // Flat corner = actual corner − h e3, rigidly linked: u_f = u − h θy, v_f = v + h θx.
    W_(6 * a, 6 * a + 4) = -h_[static_cast<std::size_t>(a)];
    W_(6 * a + 1, 6 * a + 3) = h_[static_cast<std::size_t>(a)];
    T.block<3, 3>(6 * a, 6 * a) = R0_.transpose();
    T.block<3, 3>(6 * a + 3, 6 * a + 3) = R0_.transpose();
  }
  A_ = W_ * T;
  K_lin_ = A_.transpose() * kernel_->stiffness() * A_;
  K_lin_ = 0.5 * (K_lin_ + K_lin_.transpose()).eval();
  K_bar_ = W_.transpose() * kernel_->stiffness() * W_;
  M_cons_ = A_.transpose() * kernel_->consistent_mass() * A_;
  M_cons_ = 0.5 * (M_cons_ + M_cons_.transpose()).eval();
}

void Shell4::corotational_kinematics(const Eigen::VectorXd& u, Eigen::VectorXd& d,
                                     Eigen::MatrixXd* B) const {
  const int nd = 6 * n_;
  Corners x(3, n_);
  for (int a = 0; a < n_; ++a) x.col(a) = X_[static_cast<std::size_t>(a)] + u.segment<3>(6 * a);
  Mat3 Rc;
  Vec3 c;
  Mat3N G;
  element_frame(x, Rc, c, B != nullptr ? &G : nullptr);
  d.resize(nd);
  if (B != nullptr) B->setZero(nd, nd);
  for (int a = 0; a < n_; ++a) {
    const std::size_t s = static_cast<std::size_t>(a);
    const Vec3 r = x.col(a) - c;
    d.segment<3>(6 * a) = Rc.transpose() * r - R0_.transpose() * (X_[s] - c0_);
    const Vec3 psi = u.segment<3>(6 * a + 3);
    const Vec3 th = log_so3(Rc.transpose() * exp_so3(psi) * R0_);
    d.segment<3>(6 * a + 3) = th;
    if (B == nullptr) continue;
    // δd_a = Rcᵀ(δx_a − δc + spin(r_a) δω);  δθ_a = T(θ_a)⁻¹ Rcᵀ(T(ψ_a) δψ_a − δω), δω = G δx.
    const Mat3N RtG = Rc.transpose() * G;  // 3 × 3n over corner translations
    const Mat3N RsG = Rc.transpose() * spin(r) * G;
    const Mat3 Ji = left_jacobian_inverse(th);
    const Mat3N JRtG = Ji * RtG;
    for (int b = 0; b < n_; ++b) {
      Mat3 blk = RsG.block<3, 3>(0, 3 * b) - Rc.transpose() / n_;
      if (a == b) blk += Rc.transpose();
      B->block<3, 3>(6 * a, 6 * b) = blk;
      B->block<3, 3>(6 * a + 3, 6 * b) = -JRtG.block<3, 3>(0, 3 * b);
    }
    B->block<3, 3>(6 * a + 3, 6 * a + 3) = Ji * Rc.transpose() * left_jacobian(psi);
  }
}

void Shell4::tangent(const ElementContext& ctx, const Eigen::VectorXd& u, Eigen::MatrixXd& K,
                     Eigen::VectorXd& f_int) const {
  const int nd = 6 * n_;
  if (!ctx.large_deflection) {
    K = K_lin_;
    if (ctx.stress_stiffening) {
      const Eigen::VectorXd d = A_ * u;
      K += A_.transpose() * kernel_->geometric_stiffness(d) * A_;
    }
    f_int = K * u;
    return;
  }
  Eigen::VectorXd d;
  Eigen::MatrixXd B;
  corotational_kinematics(u, d, &B);
  const Eigen::VectorXd f_l = K_bar_ * d;
  f_int = B.transpose() * f_l;
  K = B.transpose() * K_bar_ * B;
  // Geometric part ∂Bᵀ/∂u · f_l by forward differences of the analytic B (error O(h) + ε/h,
  // ~1e-7 relative with h = 1e-7 L). Its size relative to the material part is the corotated
  // strain, so below a strain of 1e-9 it cannot change Newton's convergence and is skipped.
  double L = 0.0;
  for (int a = 0; a < n_; ++a) L = std::max(L, (X_[static_cast<std::size_t>(a)] - c0_).norm());
  const double force_scale = K_bar_.diagonal().cwiseAbs().maxCoeff() * L;
  if (f_l.cwiseAbs().maxCoeff() <= 1e-9 * force_scale) return;
  Eigen::VectorXd up = u, dd;
  Eigen::MatrixXd Bp;
  const Eigen::VectorXd Btf = B.transpose() * f_l;
  for (int j = 0; j < nd; ++j) {
    const double h = (j % 6 < 3 ? L : 1.0) * 1e-7;
    up(j) = u(j) + h;
    corotational_kinematics(up, dd, &Bp);
    up(j) = u(j);
    K.col(j) += (Bp.transpose() * f_l - Btf) / h;
  }
}

void Shell4::mass(const ElementContext& ctx, Eigen::MatrixXd& M) const {
  if (!ctx.lumped_mass) {
    M = M_cons_;
    return;
  }
  // Lumped: ρtA/n on each translation, no rotary inertia; isotropic, so no transformation.
  M = kernel_->lumped_mass();
}

namespace {
const std::vector<std::string> kShell4Results = {
    "TX",     "TY",     "TXY",     "MX",     "MY",     "MXY",     "SX_TOP",   "SY_TOP",  "SXY_TOP",
    "SX_MID", "SY_MID", "SXY_MID", "SX_BOT", "SY_BOT", "SXY_BOT", "SEQV_TOP", "SEQV_BOT"};
}  // namespace

const std::vector<std::string>& Shell4::result_names() const {
  return kShell4Results;
}

Eigen::VectorXd Shell4::local_displacement(const ElementContext& ctx,
                                           const Eigen::VectorXd& u) const {
  if (!ctx.large_deflection) return A_ * u;
  Eigen::VectorXd d;
  corotational_kinematics(u, d, nullptr);
  return W_ * d;
}

void Shell4::results(const ElementContext& ctx, const Eigen::VectorXd& u, const Eigen::VectorXd&,
                     ElementResultValues& out) const {
  const shell::Resultants r = kernel_->resultants(local_displacement(ctx, u));
  // Rotate the in-plane tensors to the THETA axes.
  const double cs = std::cos(theta_), sn = std::sin(theta_);
  auto rot = [&](const Eigen::Vector3d& s) {
    return Eigen::Vector3d(s(0) * cs * cs + s(1) * sn * sn + 2.0 * s(2) * sn * cs,
                           s(0) * sn * sn + s(1) * cs * cs - 2.0 * s(2) * sn * cs,
                           (s(1) - s(0)) * sn * cs + s(2) * (cs * cs - sn * sn));
  };
  const Eigen::Vector3d N = rot(r.N), Mm = rot(r.M);
  const Eigen::Vector3d mid = N / r.t;
  const Eigen::Vector3d top = mid + 6.0 * Mm / (r.t * r.t);
  const Eigen::Vector3d bot = mid - 6.0 * Mm / (r.t * r.t);
  out = {N(0),
         N(1),
         N(2),
         Mm(0),
         Mm(1),
         Mm(2),
         top(0),
         top(1),
         top(2),
         mid(0),
         mid(1),
         mid(2),
         bot(0),
         bot(1),
         bot(2),
         von_mises(top(0), top(1), top(2)),
         von_mises(bot(0), bot(1), bot(2))};
}

namespace {

/// SHELL63, or SHELL181 (`shell181`) computed with the same thin elastic kernel.
std::unique_ptr<Element> make_shell4(const ElementBuildContext& ctx, const ElementRecord& record,
                                     bool shell181) {
  const Model& model = ctx.model;
  const auto fail = [&](const std::string& msg) {
    return InputError(record.where, fmt::format("element {}: {}", record.id, msg));
  };
  const auto type_it = model.element_types.find(record.type);
  if (type_it == model.element_types.end())
    throw fail(fmt::format("element type {} is not defined", record.type));
  const ElementType& type = type_it->second;
  Shell4Data data;
  data.shell181 = shell181;

  // Nodes: I, J, K, L; K = L (or three nodes) gives the triangle.
  std::vector<int> ids = record.nodes;
  if (ids.size() == 4 && ids[2] == ids[3]) ids.pop_back();
  if (ids.size() != 3 && ids.size() != 4)
    throw fail(fmt::format("SHELL needs nodes I, J, K, L (K = L for a triangle), got {}",
                           record.nodes.size()));
  for (std::size_t i = 0; i < ids.size(); ++i)
    for (std::size_t j = i + 1; j < ids.size(); ++j)
      if (ids[i] == ids[j]) throw fail(fmt::format("zero area: node {} repeated", ids[i]));
  for (int id : ids) {
    const auto it = model.nodes.find(id);
    if (it == model.nodes.end()) throw fail(fmt::format("node {} is not defined", id));
    data.positions.push_back(it->second.x);
  }
  data.node_ids = ids;

  // Material.
  const auto mat_it = model.materials.find(record.mat);
  if (mat_it == model.materials.end() || !mat_it->second.has("EX"))
    throw fail(fmt::format("material {} has no EX", record.mat));
  const Material& mat = mat_it->second;
  shell::KernelData& k = data.kernel;
  k.E = mat.get("EX", 0.0);
  if (!(k.E > 0.0)) throw fail(fmt::format("material {}: EX must be positive", record.mat));
  k.nu = mat.has("NUXY") ? mat.get("NUXY", 0.3) : mat.get("PRXY", 0.3);
  k.rho = mat.get("DENS", 0.0);

  // Thickness: SHELL181 section (SECTYPE SHELL / SECDATA) or real constants TK(I..L).
  const auto sec_it = model.sections.find(record.secnum);
  const RealSet* real = nullptr;
  if (const auto it = model.real_sets.find(record.real); it != model.real_sets.end())
    real = &it->second;
  if (record.secnum > 0 && sec_it != model.sections.end() && !sec_it->second.data.empty()) {
    k.t.fill(sec_it->second.data[0]);
  } else {
    if (real == nullptr)
      throw fail(fmt::format("real constant set {} is not defined", record.real));
    const double ti = real->get(1);
    for (int i = 0; i < 4; ++i) {
      const double t = real->get(i + 1);
      k.t[static_cast<std::size_t>(i)] = t != 0.0 ? t : ti;
    }
    if (ids.size() == 3) k.t[2] = real->get(3) != 0.0 ? real->get(3) : ti;
  }
  for (std::size_t i = 0; i < ids.size(); ++i)
    if (!(k.t[i] > 0.0)) throw fail("zero or negative thickness");
  if (real != nullptr && record.secnum == 0) {
    k.efs = real->get(5);
    data.theta_deg = real->get(6);
    k.rmi = real->get(7) != 0.0 ? real->get(7) : 1.0;
    k.added_mass = real->get(19);
  }
  k.membrane = type.key(1) != 2;
  k.bending = type.key(1) != 1;
  k.extra_shapes = type.key(3) != 2;
  k.rotary_inertia = type.key(7) != 1;
  return std::make_unique<Shell4>(record.id, data, record.where);
}

ElementTypeDescriptor shell_type(const char* name, int number, bool shell181) {
  return {
      .name = name,
      .number = number,
      .family = "Shell4",
      .n_nodes = 4,
      .min_nodes = 3,
      .real_constants = RealConstantUse::UnlessSection,
      .needs_material = true,
      .section_types = {"SHELL"},
      .vtk_cell = VtkCell::Quad,
      .result_names = kShell4Results,
      // S at the top surface (MAPDL's default shell location); SMISC 1-6 = T and M resultants.
      .result_sequences = {{"S", "X", "SX_TOP"},
                           {"S", "Y", "SY_TOP"},
                           {"S", "XY", "SXY_TOP"},
                           {"S", "EQV", "SEQV_TOP"},
                           {"SMISC", "1", "TX"},
                           {"SMISC", "2", "TY"},
                           {"SMISC", "3", "TXY"},
                           {"SMISC", "4", "MX"},
                           {"SMISC", "5", "MY"},
                           {"SMISC", "6", "MXY"}},
      .note = shell181 ? "SHELL181 is computed with the SHELL63 kernel (thin elastic shell)" : "",
      .create = [shell181](const ElementBuildContext& ctx, const ElementRecord& record) {
        return make_shell4(ctx, record, shell181);
      }};
}

const ElementRegistration kShell63{shell_type("SHELL63", 63, false)};
const ElementRegistration kShell181{shell_type("SHELL181", 181, true)};

}  // namespace

}  // namespace impactfe
