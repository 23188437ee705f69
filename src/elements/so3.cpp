#include "elements/so3.h"

#include <Eigen/Geometry>

#include <cmath>

namespace impactfe::so3 {

namespace {

/// Coefficients of F(ψ) = I + α S + β S² and of its derivative: dα = α'(t)/t, dβ = β'(t)/t,
/// so that ∂α/∂ψ = dα ψᵀ (finite at t = 0, unlike α'(t)).
struct RodriguesCoefficients {
  double alpha = 0.0, d_alpha = 0.0, beta = 0.0, d_beta = 0.0;
};

// Below this angle the derivative coefficients come from their Taylor series (4 terms, error
// < t⁸/6e5 ≈ 1e-11 relative); above it the closed forms lose at most ~1e-11 to cancellation.
constexpr double kSeriesAngle = 0.3;

/// T(ψ): α = (1 − cos t)/t², β = (t − sin t)/t³; the derivative coefficients only when asked
/// for (the maps alone are evaluated at every corner and iterate).
RodriguesCoefficients left_jacobian_coefficients(double t, bool derivatives = true) {
  RodriguesCoefficients k;
  if (t < 1e-4) {
    k.alpha = 0.5 - t * t / 24.0;
    k.beta = 1.0 / 6.0 - t * t / 120.0;
  } else {
    k.alpha = (1.0 - std::cos(t)) / (t * t);
    k.beta = (t - std::sin(t)) / (t * t * t);
  }
  if (!derivatives) return k;
  const double t2 = t * t;
  if (t < kSeriesAngle) {
    k.d_alpha = -1.0 / 12.0 + t2 * (1.0 / 180.0 + t2 * (-1.0 / 6720.0 + t2 / 453600.0));
    k.d_beta = -1.0 / 60.0 + t2 * (1.0 / 1260.0 + t2 * (-1.0 / 60480.0 + t2 / 4989600.0));
  } else {
    const double s = std::sin(t), c = std::cos(t);
    k.d_alpha = (t * s - 2.0 * (1.0 - c)) / (t2 * t2);
    k.d_beta = (t * (1.0 - c) - 3.0 * (t - s)) / (t2 * t2 * t);
  }
  return k;
}

/// T(ψ)⁻¹: α = −1/2, β = 1/t² − (1 + cos t)/(2 t sin t) = 1/t² − cot(t/2)/(2t).
RodriguesCoefficients left_jacobian_inverse_coefficients(double t, bool derivatives = true) {
  RodriguesCoefficients k;
  k.alpha = -0.5;
  if (t < 1e-4)
    k.beta = 1.0 / 12.0 + t * t / 720.0;
  else
    k.beta = 1.0 / (t * t) - (1.0 + std::cos(t)) / (2.0 * t * std::sin(t));
  if (!derivatives) return k;
  const double t2 = t * t;
  if (t < kSeriesAngle) {
    k.d_beta = 1.0 / 360.0 + t2 * (1.0 / 7560.0 + t2 * (1.0 / 201600.0 + t2 / 5987520.0));
  } else {
    // β' = −2/t³ + 1/(4 t sin²(t/2)) + cot(t/2)/(2t²).
    const double sh = std::sin(0.5 * t);
    k.d_beta =
        -2.0 / (t2 * t2) + 1.0 / (4.0 * t2 * sh * sh) + std::cos(0.5 * t) / (sh * 2.0 * t2 * t);
  }
  return k;
}

Mat3 rodrigues(const Vec3& psi, const RodriguesCoefficients& k) {
  const Mat3 S = spin(psi);
  return Mat3::Identity() + k.alpha * S + k.beta * S * S;
}

/// ∂(Fᵀ v)/∂ψ with Fᵀ v = v − α S v + β S² v (Sᵀ = −S), using ∂(ψ × v)/∂ψ = −spin(v) and
/// ∂(ψ × (ψ × v))/∂ψ = ∂(ψ (ψ·v) − v (ψ·ψ))/∂ψ = ψ vᵀ + (ψ·v) I − 2 v ψᵀ.
Mat3 d_rodrigues_transpose(const Vec3& psi, const Vec3& v, const RodriguesCoefficients& k) {
  const Vec3 Sv = psi.cross(v);
  const Vec3 SSv = psi.cross(Sv);
  return -k.d_alpha * Sv * psi.transpose() + k.alpha * spin(v) + k.d_beta * SSv * psi.transpose() +
         k.beta * (psi * v.transpose() + psi.dot(v) * Mat3::Identity() - 2.0 * v * psi.transpose());
}

}  // namespace

Mat3 spin(const Vec3& v) {
  Mat3 S;
  S << 0.0, -v.z(), v.y(), v.z(), 0.0, -v.x(), -v.y(), v.x(), 0.0;
  return S;
}

Mat3 exp_map(const Vec3& psi) {
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

void exp_quaternion_and_left_jacobian(const Vec3& psi, Eigen::Quaterniond& q, Mat3& T) {
  const double t = psi.norm();
  const double sh = std::sin(0.5 * t), ch = std::cos(0.5 * t);
  // sin(t/2)/t: its series below 1e-6 (error < t⁴/4e4 relative).
  const double sinc_half = t < 1e-6 ? 0.5 - t * t / 48.0 : sh / t;
  q.w() = ch;
  q.vec() = sinc_half * psi;
  RodriguesCoefficients k;
  if (t < 1e-4) {
    k.alpha = 0.5 - t * t / 24.0;
    k.beta = 1.0 / 6.0 - t * t / 120.0;
  } else {
    k.alpha = 2.0 * sh * sh / (t * t);  // (1 − cos t)/t², without its cancellation
    k.beta = (t - 2.0 * sh * ch) / (t * t * t);
  }
  T = rodrigues(psi, k);
}

Vec3 log_map(const Mat3& R) {
  Eigen::Quaterniond q(R);
  if (q.w() < 0.0) q.coeffs() *= -1.0;
  const Vec3 v = q.vec();
  const double s = v.norm();
  if (s < 1e-12) return 2.0 * v;
  return (2.0 * std::atan2(s, q.w()) / s) * v;
}

Vec3 log_quaternion_and_left_jacobian_inverse(Eigen::Quaterniond q, Mat3& Ji) {
  if (q.w() < 0.0) q.coeffs() *= -1.0;
  const Vec3 v = q.vec();
  const double s = v.norm(), w = q.w();  // sin(t/2), cos(t/2) of the angle t
  const Vec3 theta = s < 1e-12 ? Vec3(2.0 * v) : Vec3((2.0 * std::atan2(s, w) / s) * v);
  // T(θ)⁻¹'s β = 1/t² − (1 + cos t)/(2 t sin t) = 1/t² − w/(2 t s), as 1 + cos t = 2w² and
  // sin t = 2ws: no trigonometric call beyond the angle's.
  const double t = theta.norm();
  const double beta = t < 1e-4 ? 1.0 / 12.0 + t * t / 720.0 : 1.0 / (t * t) - w / (2.0 * t * s);
  const Mat3 S = spin(theta);
  Ji = Mat3::Identity() - 0.5 * S + beta * S * S;
  return theta;
}

Mat3 left_jacobian(const Vec3& psi) {
  return rodrigues(psi, left_jacobian_coefficients(psi.norm(), false));
}

Mat3 left_jacobian_inverse(const Vec3& psi) {
  return rodrigues(psi, left_jacobian_inverse_coefficients(psi.norm(), false));
}

Mat3 d_left_jacobian_transpose(const Vec3& psi, const Vec3& v) {
  return d_rodrigues_transpose(psi, v, left_jacobian_coefficients(psi.norm()));
}

Mat3 d_left_jacobian_inverse_transpose(const Vec3& theta, const Vec3& m) {
  return d_rodrigues_transpose(theta, m, left_jacobian_inverse_coefficients(theta.norm()));
}

}  // namespace impactfe::so3
