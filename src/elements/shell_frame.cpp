#include "elements/shell_frame.h"

#include <Eigen/Dense>

#include "elements/so3.h"

namespace impactfe {

// The 3n × 3n products below have inner dimension 3: lazyProduct keeps them coefficient-based
// (Eigen would otherwise send these small dynamic-size products through its blocked GEMM).

namespace {

using Mat3 = Eigen::Matrix3d;
using Vec3 = Eigen::Vector3d;
using RowN = Eigen::Matrix<double, 1, Eigen::Dynamic, Eigen::RowMajor, 1, 12>;
using so3::spin;

/// ∂(x[i1] − x[i0])/∂x (3 × 3n).
ShellMat3N difference_selector(int n, int i1, int i0) {
  ShellMat3N S = ShellMat3N::Zero(3, 3 * n);
  S.block<3, 3>(0, 3 * i1) += Mat3::Identity();
  S.block<3, 3>(0, 3 * i0) -= Mat3::Identity();
  return S;
}

/// Hessian of y·(q/|q|) with respect to q, at e = q/|q|, L = |q|:
/// (3 (y·e) e eᵀ − (y·e) I − y eᵀ − e yᵀ) / L².
Mat3 unit_vector_hessian(const Vec3& e, double L, const Vec3& y) {
  const double ye = y.dot(e);
  return (3.0 * ye * e * e.transpose() - ye * Mat3::Identity() - y * e.transpose() -
          e * y.transpose()) /
         (L * L);
}

}  // namespace

ShellFrame shell_frame(const ShellCorners& x, bool with_derivatives) {
  ShellFrame f;
  const int n = static_cast<int>(x.cols());
  f.n = n;
  f.c = x.rowwise().mean();
  int ia0, ia1, ib0, ib1;  // a = x[ia1] − x[ia0], b = x[ib1] − x[ib0]
  if (n == 4) {
    ia0 = 0, ia1 = 2, ib0 = 1, ib1 = 3;
  } else {
    ia0 = 0, ia1 = 1, ib0 = 0, ib1 = 2;
  }
  const Vec3 a = x.col(ia1) - x.col(ia0);
  const Vec3 b = x.col(ib1) - x.col(ib0);
  const Vec3 nvec = a.cross(b);
  const double nn = nvec.norm();
  const Vec3 e3 = nvec / nn;
  const Vec3 v = x.col(1) - x.col(0);
  const Vec3 p = v - v.dot(e3) * e3;
  const double pn = p.norm();
  const Vec3 e1 = p / pn;
  const Vec3 e2 = e3.cross(e1);
  f.R.col(0) = e1;
  f.R.col(1) = e2;
  f.R.col(2) = e3;
  if (!with_derivatives) return f;
  f.a = a, f.b = b, f.v = v, f.n_norm = nn, f.p_norm = pn;
  f.Sa = difference_selector(n, ia1, ia0);
  f.Sb = difference_selector(n, ib1, ib0);
  f.Sv = difference_selector(n, 1, 0);
  // d(a×b) = −spin(b) da + spin(a) db, with da, db selecting corner translations.
  ShellMat3N& Dn = f.Dn;
  Dn = ShellMat3N::Zero(3, 3 * n);
  Dn.block<3, 3>(0, 3 * ia1) -= spin(b);
  Dn.block<3, 3>(0, 3 * ia0) += spin(b);
  Dn.block<3, 3>(0, 3 * ib1) += spin(a);
  Dn.block<3, 3>(0, 3 * ib0) -= spin(a);
  f.De3 = (Mat3::Identity() - e3 * e3.transpose()) / nn * Dn;
  const ShellMat3N& De3 = f.De3;
  const RowN w1 = -e2.transpose() * De3;
  const RowN w2 = e1.transpose() * De3;
  RowN dv = RowN::Zero(1, 3 * n);  // e2ᵀ d(x1 − x0)
  dv.segment<3>(3) += e2.transpose();
  dv.segment<3>(0) -= e2.transpose();
  const RowN w3 = (dv - v.dot(e3) * e2.transpose() * De3) / pn;  // = e2ᵀ ∂e1/∂x
  f.G = e1 * w1 + e2 * w2 + e3 * w3;
  // p = v − (v·e3) e3: dp = Sv dx − e3 d(v·e3) − (v·e3) de3, d(v·e3) = (e3ᵀ Sv + vᵀ De3) dx.
  const RowN d_alpha = e3.transpose() * f.Sv + v.transpose() * De3;
  f.Dp = f.Sv - e3 * d_alpha - v.dot(e3) * De3;
  f.De1 = (Mat3::Identity() - e1 * e1.transpose()) / pn * f.Dp;
  return f;
}

// The Hessians below run once per element and Newton iterate (the geometric tangent): they are
// written for a fixed corner count (N3 = 3n = 9 or 12) on maps of the frame's fixed-capacity
// matrices (3 × 3n, stored contiguously), so Eigen unrolls the small products.
namespace {

template <int N3>
using Mat3N = Eigen::Matrix<double, 3, N3>;
template <int N3>
using MatNN = Eigen::Matrix<double, N3, N3>;
template <int N3>
using VecN = Eigen::Matrix<double, N3, 1>;

template <int N3>
Eigen::Map<const Mat3N<N3>> fixed(const ShellMat3N& m) {
  return Eigen::Map<const Mat3N<N3>>(m.data());
}

// y·e3 = φ(n_vec) with n_vec = a × b bilinear in x:
//   H = Dnᵀ (∂²φ/∂n²) Dn + ∂²(g·(a×b))/∂x², g = ∂φ/∂n = (I − e3e3ᵀ) y / |n|,
// and g·(δa × δ'b + δ'a × δb) = δxᵀ (Sbᵀ spin(g) Sa − Saᵀ spin(g) Sb) δ'x.
template <int N3>
MatNN<N3> normal_hessian_n(const ShellFrame& f, const Vec3& y) {
  const auto Dn = fixed<N3>(f.Dn), Sa = fixed<N3>(f.Sa), Sb = fixed<N3>(f.Sb);
  const Vec3 e3 = f.e3();
  const Vec3 g = (y - e3 * e3.dot(y)) / f.n_norm;
  const Mat3 Sg = spin(g);
  const Mat3N<N3> HDn = unit_vector_hessian(e3, f.n_norm, y) * Dn;
  const Mat3N<N3> SgSa = Sg * Sa;
  const Mat3N<N3> SgSb = Sg * Sb;
  MatNN<N3> H = Dn.transpose().lazyProduct(HDn);
  H += Sb.transpose().lazyProduct(SgSa) - Sa.transpose().lazyProduct(SgSb);
  return H;
}

// y·e1 = φ(p) with p = v − α e3, α = v·e3:
//   H = Dpᵀ (∂²φ/∂p²) Dp + ∂²(g·p)/∂x² at g = (I − e1e1ᵀ) y / |p| fixed, where
//   g·p = g·v − α β (β = g·e3, g·v linear) and
//   ∂²(αβ) = ∇α∇βᵀ + ∇β∇αᵀ + β (Svᵀ De3 + De3ᵀ Sv) + ∂²((β v + α g)·e3)  (v, g held fixed).
template <int N3>
MatNN<N3> side_hessian_n(const ShellFrame& f, const Vec3& y) {
  const auto Sv = fixed<N3>(f.Sv), De3 = fixed<N3>(f.De3), Dp = fixed<N3>(f.Dp);
  const Vec3 e1 = f.e1(), e3 = f.e3();
  const Vec3 g = (y - e1 * e1.dot(y)) / f.p_norm;
  const double alpha = f.v.dot(e3), beta = g.dot(e3);
  const VecN<N3> grad_alpha = Sv.transpose() * e3 + De3.transpose() * f.v;
  const VecN<N3> grad_beta = De3.transpose() * g;
  const MatNN<N3> SvDe3 = Sv.transpose().lazyProduct(De3);
  const Mat3N<N3> HDp = unit_vector_hessian(e1, f.p_norm, y) * Dp;
  MatNN<N3> H = Dp.transpose().lazyProduct(HDp);
  H -=
      grad_alpha.lazyProduct(grad_beta.transpose()) + grad_beta.lazyProduct(grad_alpha.transpose());
  H -= beta * (SvDe3 + SvDe3.transpose());
  H -= normal_hessian_n<N3>(f, beta * f.v + alpha * g);
  return H;
}

// Gᵀ w = De3ᵀ (−s1 e2 + s2 e1) + s3 De1ᵀ e2 with s_i = e_i·w. At fixed w its variation has
// three parts: δs_i = (e_i × w)·δω gives Gᵀ spin(w) G; δe_j = δω × e_j = −spin(e_j) G δx in the
// vectors multiplying De3, De1; and the Hessians of e3 and e1 along those vectors.
template <int N3>
MatNN<N3> frame_spin_derivative_n(const ShellFrame& f, const Vec3& w) {
  const auto G = fixed<N3>(f.G), De3 = fixed<N3>(f.De3), De1 = fixed<N3>(f.De1);
  const Vec3 e1 = f.e1(), e2 = f.e2(), e3 = f.e3();
  const double s1 = e1.dot(w), s2 = e2.dot(w), s3 = e3.dot(w);
  const Mat3N<N3> WG = spin(w) * G;
  const Mat3N<N3> E3G = (s1 * spin(e2) - s2 * spin(e1)) * G;
  const Mat3N<N3> E1G = (s3 * spin(e2)) * G;
  MatNN<N3> H = G.transpose().lazyProduct(WG);
  H += De3.transpose().lazyProduct(E3G);
  H -= De1.transpose().lazyProduct(E1G);
  H += normal_hessian_n<N3>(f, -s1 * e2 + s2 * e1);
  H += side_hessian_n<N3>(f, s3 * e2);
  return H;
}

}  // namespace

ShellMatNN normal_hessian(const ShellFrame& f, const Vec3& y) {
  if (f.n == 4) return normal_hessian_n<12>(f, y);
  return normal_hessian_n<9>(f, y);
}

ShellMatNN side_hessian(const ShellFrame& f, const Vec3& y) {
  if (f.n == 4) return side_hessian_n<12>(f, y);
  return side_hessian_n<9>(f, y);
}

ShellMatNN frame_spin_derivative(const ShellFrame& f, const Vec3& w) {
  if (f.n == 4) return frame_spin_derivative_n<12>(f, w);
  return frame_spin_derivative_n<9>(f, w);
}

Eigen::Vector3d shell_esys_x_axis(const Eigen::Matrix3d& local_axes, const Eigen::Vector3d& n) {
  const Eigen::Vector3d x = local_axes.col(0) - local_axes.col(0).dot(n) * n;
  if (x.norm() > 1e-3) return x.normalized();
  const Eigen::Vector3d y = local_axes.col(1) - local_axes.col(1).dot(n) * n;
  return y.normalized().cross(n);
}

}  // namespace impactfe
