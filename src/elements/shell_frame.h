#pragma once
/// The co-rotated frame of a 3- or 4-node shell facet and its first and second derivatives with
/// respect to the corner positions (the element-independent co-rotational formulation of
/// Rankin & Nour-Omid 1988 / Nour-Omid & Rankin 1991; Felippa & Haugen 2005, §§5–7;
/// Crisfield vol. 2, §17.3).
///
/// e3 is the facet normal ((x2 − x0) × (x3 − x1) for a quad, i.e. the mean plane;
/// (x1 − x0) × (x2 − x0) for a triangle), e1 the side x0 → x1 projected on the plane,
/// e2 = e3 × e1, c the centroid. The frame spin δω (δe_i = δω × e_i) of corner translation
/// variations δx (3n, corner-major) is δω = G δx, with
///     G = e1 (−e2ᵀ ∂e3/∂x) + e2 (e1ᵀ ∂e3/∂x) + e3 (e2ᵀ ∂e1/∂x).
/// The consistent tangent also needs ∂(Gᵀ w)/∂x at a fixed vector w: frame_spin_derivative.
#include <Eigen/Core>

namespace impactfe {

/// Fixed-capacity types (at most 4 corners): the frame is evaluated for every element at every
/// Newton iteration, so it must not touch the heap.
using ShellCorners = Eigen::Matrix<double, 3, Eigen::Dynamic, Eigen::ColMajor, 3, 4>;
using ShellMat3N = Eigen::Matrix<double, 3, Eigen::Dynamic, Eigen::ColMajor, 3, 12>;
using ShellVecN = Eigen::Matrix<double, Eigen::Dynamic, 1, Eigen::ColMajor, 12, 1>;
using ShellMatNN = Eigen::Matrix<double, Eigen::Dynamic, Eigen::Dynamic, Eigen::ColMajor, 12, 12>;

struct ShellFrame {
  int n = 0;                                        // corners
  Eigen::Matrix3d R = Eigen::Matrix3d::Identity();  // columns e1, e2, e3
  Eigen::Vector3d c = Eigen::Vector3d::Zero();      // centroid
  // With derivatives only:
  ShellMat3N G;  // frame spin δω = G δx
  // Intermediate quantities of the derivatives: n_vec = a × b with a = Sa x, b = Sb x
  // (differences of corners), v = Sv x = x1 − x0, p = v − (v·e3) e3 (e1 = p/|p|).
  Eigen::Vector3d a, b, v;
  double n_norm = 0.0, p_norm = 0.0;
  ShellMat3N Sa, Sb, Sv;  // constant selection matrices
  ShellMat3N Dn, De3;     // ∂n_vec/∂x, ∂e3/∂x
  ShellMat3N Dp, De1;     // ∂p/∂x, ∂e1/∂x
  const Eigen::Vector3d e1() const { return R.col(0); }
  const Eigen::Vector3d e2() const { return R.col(1); }
  const Eigen::Vector3d e3() const { return R.col(2); }
};

/// Frame of the corner positions x (3 × n, n = 3 or 4); with_derivatives also fills G and the
/// first derivatives. R has NaNs for a degenerate (zero-area) facet.
ShellFrame shell_frame(const ShellCorners& x, bool with_derivatives);

/// Hessian ∂²(y·e3)/∂x² for a fixed vector y (3n × 3n, symmetric).
ShellMatNN normal_hessian(const ShellFrame& f, const Eigen::Vector3d& y);

/// Hessian ∂²(y·e1)/∂x² for a fixed vector y (3n × 3n, symmetric).
ShellMatNN side_hessian(const ShellFrame& f, const Eigen::Vector3d& y);

/// ∂(Gᵀ w)/∂x for a fixed vector w (3n × 3n): the variation of the frame spin operator, i.e.
/// the second derivatives of the frame (the "rotational" geometric stiffness of the
/// co-rotated frame; Felippa & Haugen 2005, §7.3, there obtained for the triangle only).
ShellMatNN frame_spin_derivative(const ShellFrame& f, const Eigen::Vector3d& w);

/// The element x axis that ESYS gives a shell whose unit normal at a point is `n`: the local x
/// axis projected on the tangent plane (MAPDL's ESYS for shells) or, when that projection is
/// shorter than 10⁻³ (the axis within 0.06° of the normal), the local y axis projected and
/// turned −90° about the normal, so that it becomes the element y axis.
Eigen::Vector3d shell_esys_x_axis(const Eigen::Matrix3d& local_axes, const Eigen::Vector3d& n);

}  // namespace impactfe
