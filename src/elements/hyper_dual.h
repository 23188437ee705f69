#pragma once
/// Second-order forward automatic differentiation: a number carrying its value, gradient and
/// Hessian with respect to N variables (Griewank & Walther, Evaluating Derivatives, 2nd ed.,
/// §13: Taylor propagation to second order; the chain rule
/// h(f∘x) = f'(x) h(x) + f''(x) ∇x ∇xᵀ). The contact kinematics of a node against a deformable
/// facet or a rotating rigid target are written once as a function of the element's DOF values
/// and differentiated exactly through it: the gradients of the gap and of the tangential
/// displacement and the curvature terms of the consistent tangent, to round-off, with no
/// hand-derived second variations to get wrong. Used with N ≤ 12, i.e. a few hundred small
/// fixed-size operations per contact point and iteration.
#include <Eigen/Core>
#include <array>
#include <cmath>

namespace impactfe::ad {

template <int N>
struct Dual2 {
  using Grad = Eigen::Matrix<double, N, 1>;
  using Hess = Eigen::Matrix<double, N, N>;
  double v = 0.0;
  Grad g = Grad::Zero();
  Hess h = Hess::Zero();

  Dual2() = default;
  Dual2(double value) : v(value) {}  // NOLINT: a constant converts implicitly
  /// The independent variable i with value `value`.
  static Dual2 variable(double value, int i) {
    Dual2 d(value);
    d.g(i) = 1.0;
    return d;
  }
};

template <int N>
Dual2<N> operator+(const Dual2<N>& a, const Dual2<N>& b) {
  Dual2<N> r;
  r.v = a.v + b.v;
  r.g = a.g + b.g;
  r.h = a.h + b.h;
  return r;
}
template <int N>
Dual2<N> operator-(const Dual2<N>& a, const Dual2<N>& b) {
  Dual2<N> r;
  r.v = a.v - b.v;
  r.g = a.g - b.g;
  r.h = a.h - b.h;
  return r;
}
template <int N>
Dual2<N> operator-(const Dual2<N>& a) {
  Dual2<N> r;
  r.v = -a.v;
  r.g = -a.g;
  r.h = -a.h;
  return r;
}
template <int N>
Dual2<N> operator*(const Dual2<N>& a, const Dual2<N>& b) {
  Dual2<N> r;
  r.v = a.v * b.v;
  r.g = a.v * b.g + b.v * a.g;
  r.h = a.v * b.h + b.v * a.h + a.g * b.g.transpose() + b.g * a.g.transpose();
  return r;
}
template <int N>
Dual2<N> operator*(double a, const Dual2<N>& b) {
  Dual2<N> r;
  r.v = a * b.v;
  r.g = a * b.g;
  r.h = a * b.h;
  return r;
}
/// f(x) from f, f', f'' at x.v (the chain rule to second order).
template <int N>
Dual2<N> chain(const Dual2<N>& x, double f, double df, double d2f) {
  Dual2<N> r;
  r.v = f;
  r.g = df * x.g;
  r.h = df * x.h + d2f * x.g * x.g.transpose();
  return r;
}
template <int N>
Dual2<N> inverse(const Dual2<N>& x) {
  const double i = 1.0 / x.v;
  return chain(x, i, -i * i, 2.0 * i * i * i);
}
template <int N>
Dual2<N> operator/(const Dual2<N>& a, const Dual2<N>& b) {
  return a * inverse(b);
}
template <int N>
Dual2<N> sqrt(const Dual2<N>& x) {
  const double s = std::sqrt(x.v);
  return chain(x, s, 0.5 / s, -0.25 / (s * x.v));
}

/// A 3-vector of Dual2 numbers.
template <int N>
using V3 = std::array<Dual2<N>, 3>;

template <int N>
V3<N> constant(const Eigen::Vector3d& c) {
  return {Dual2<N>(c(0)), Dual2<N>(c(1)), Dual2<N>(c(2))};
}
/// The vector c + (variables first .. first+2).
template <int N>
V3<N> variables(const Eigen::Vector3d& c, const Eigen::Matrix<double, N, 1>& u, int first) {
  V3<N> r;
  for (int d = 0; d < 3; ++d) r[d] = Dual2<N>::variable(c(d) + u(first + d), first + d);
  return r;
}
template <int N>
V3<N> operator+(const V3<N>& a, const V3<N>& b) {
  return {a[0] + b[0], a[1] + b[1], a[2] + b[2]};
}
template <int N>
V3<N> operator-(const V3<N>& a, const V3<N>& b) {
  return {a[0] - b[0], a[1] - b[1], a[2] - b[2]};
}
template <int N>
V3<N> operator*(const Dual2<N>& s, const V3<N>& a) {
  return {s * a[0], s * a[1], s * a[2]};
}
template <int N>
Dual2<N> dot(const V3<N>& a, const V3<N>& b) {
  return a[0] * b[0] + a[1] * b[1] + a[2] * b[2];
}
template <int N>
V3<N> cross(const V3<N>& a, const V3<N>& b) {
  return {a[1] * b[2] - a[2] * b[1], a[2] * b[0] - a[0] * b[2], a[0] * b[1] - a[1] * b[0]};
}
template <int N>
Dual2<N> dot(const Eigen::Vector3d& a, const V3<N>& b) {
  return a(0) * b[0] + a(1) * b[1] + a(2) * b[2];
}

/// R(ψ) a for the rotation vector ψ (Rodrigues: R = I + α S + β S², S = spin(ψ),
/// α = sin t / t, β = (1 − cos t)/t², t = |ψ|). α and β are taken as functions of s = t² = ψ·ψ,
/// smooth at ψ = 0 (Taylor series below t = 0.3, where the closed forms lose digits), so the
/// derivatives are exact at and near the identity too.
template <int N>
V3<N> rotate(const V3<N>& psi, const V3<N>& a) {
  const Dual2<N> s = dot(psi, psi);
  const double x = s.v;
  double al, dal, ddal, be, dbe, ddbe;
  if (x < 0.09) {
    al = 1.0 + x * (-1.0 / 6 + x * (1.0 / 120 + x * (-1.0 / 5040 + x / 362880)));
    dal = -1.0 / 6 + x * (2.0 / 120 + x * (-3.0 / 5040 + x * 4.0 / 362880));
    ddal = 2.0 / 120 + x * (-6.0 / 5040 + x * 12.0 / 362880);
    be = 0.5 + x * (-1.0 / 24 + x * (1.0 / 720 + x * (-1.0 / 40320 + x / 3628800)));
    dbe = -1.0 / 24 + x * (2.0 / 720 + x * (-3.0 / 40320 + x * 4.0 / 3628800));
    ddbe = 2.0 / 720 + x * (-6.0 / 40320 + x * 12.0 / 3628800);
  } else {
    // d/ds = (1/2t) d/dt and d²/ds² = (f'' − f'/t)/(4t²).
    const double t = std::sqrt(x), sn = std::sin(t), cs = std::cos(t);
    al = sn / t;
    const double a1 = (t * cs - sn) / (t * t), a2 = -sn / t - 2.0 * cs / (t * t) + 2.0 * sn / x / t;
    be = (1.0 - cs) / x;
    const double b1 = sn / x - 2.0 * (1.0 - cs) / (x * t);
    const double b2 = cs / x - 4.0 * sn / (x * t) + 6.0 * (1.0 - cs) / (x * x);
    dal = a1 / (2.0 * t);
    ddal = (a2 - a1 / t) / (4.0 * x);
    dbe = b1 / (2.0 * t);
    ddbe = (b2 - b1 / t) / (4.0 * x);
  }
  const Dual2<N> alpha = chain(s, al, dal, ddal), beta = chain(s, be, dbe, ddbe);
  const V3<N> sa = cross(psi, a);
  const V3<N> ssa = cross(psi, sa);
  return a + alpha * sa + beta * ssa;
}

}  // namespace impactfe::ad
