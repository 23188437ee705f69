#pragma once
/// Finite rotations (the group SO(3)) for the co-rotational shell: the rotation-vector maps exp
/// and log, the left Jacobian T(ψ) of exp and its inverse, and the exact derivatives of
/// T(ψ)ᵀv and T(ψ)⁻ᵀv with respect to the rotation vector that the consistent tangent needs.
///
/// Every map here has the Rodrigues form F(ψ) = I + α(t) S + β(t) S² with S = spin(ψ), t = |ψ|
/// (Crisfield, Non-linear Finite Element Analysis of Solids and Structures vol. 2, §16.2 and
/// §17.2; Nour-Omid & Rankin 1991, CMAME 93, eqs. 24–30; Felippa & Haugen 2005, CMAME 194,
/// §§4–5, where T is called H and T⁻¹ is H⁻¹). Near t = 0 the coefficients are evaluated from
/// their Taylor series, so the maps and their derivatives are exact to round-off for all t < π.
#include <Eigen/Core>
#include <Eigen/Geometry>

namespace impactfe::so3 {

using Vec3 = Eigen::Vector3d;
using Mat3 = Eigen::Matrix3d;

/// spin(v) w = v × w.
Mat3 spin(const Vec3& v);

/// Rotation matrix of the rotation vector ψ (Rodrigues: α = sin t / t, β = (1 − cos t)/t²).
Mat3 exp_map(const Vec3& psi);

/// exp(ψ) as a unit quaternion (cos(t/2), sin(t/2) ψ/t) and left_jacobian(ψ), both from one
/// sine and cosine of t/2 (sin t = 2 sin(t/2) cos(t/2), 1 − cos t = 2 sin²(t/2)): equal to
/// exp_map and left_jacobian to round-off. Composed as quaternions, three rotations cost 32
/// multiplications instead of 54 for two 3 × 3 products and a conversion (the co-rotational
/// triangle's θ = log(Rcᵀ exp(ψ) R0) at every corner and residual, issue 11).
void exp_quaternion_and_left_jacobian(const Vec3& psi, Eigen::Quaterniond& q, Mat3& T);

/// Rotation vector of R, angle in [0, π] (via the quaternion, robust near 0 and π).
Vec3 log_map(const Mat3& R);

/// The rotation vector θ of the unit quaternion q (q and −q are the same rotation) and T(θ)⁻¹:
/// the inverse Jacobian's coefficient from the half-angle's sine and cosine (equal to
/// left_jacobian_inverse(θ) to round-off).
Vec3 log_quaternion_and_left_jacobian_inverse(Eigen::Quaterniond q, Mat3& Ji);

/// Left Jacobian T(ψ) of exp: δR Rᵀ = spin(T(ψ) δψ); α = (1 − cos t)/t², β = (t − sin t)/t³.
Mat3 left_jacobian(const Vec3& psi);

/// T(ψ)⁻¹: α = −1/2, β = 1/t² − (1 + cos t)/(2 t sin t) (Felippa & Haugen 2005, eq. 57).
Mat3 left_jacobian_inverse(const Vec3& psi);

/// ∂(T(ψ)ᵀ v)/∂ψ for a fixed vector v (3 × 3).
Mat3 d_left_jacobian_transpose(const Vec3& psi, const Vec3& v);

/// ∂(T(θ)⁻ᵀ m)/∂θ for a fixed vector m (3 × 3).
Mat3 d_left_jacobian_inverse_transpose(const Vec3& theta, const Vec3& m);

}  // namespace impactfe::so3
