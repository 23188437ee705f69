#pragma once
/// Axial kinematics of a two-node member (spar, longitudinal spring) in 1, 2 or 3 components:
/// small deflection, small deflection with stress stiffening, and co-rotational large deflection.
/// Vectors are [u_I; u_J] (d components per node); blk(A) = [A −A; −A A] (spec §11).
#include <fmt/format.h>
#include <Eigen/Core>

#include <cmath>

#include "core/errors.h"

namespace impactfe::corotational {

/// How the axial force and its tangent follow the displacement.
enum class AxialKinematics {
  /// N = k n·Δu + N0, f = N[−n; n], K = k blk(nnᵀ).
  Linear,
  /// Stress stiffening in small deflection: extension e = n·Δu + |PΔu|²/(2L), P = I − nnᵀ, the
  /// second-order (moderate-rotation) strain, so that K_T = k blk(ggᵀ) + (N/L) blk(P) with
  /// g = n + PΔu/L is the exact derivative of f = N[−g; g]. At u = 0 this is the spec's
  /// K + (N/L) blk(I − nnᵀ) (Cook et al. §18.3).
  StressStiffened,
  /// Co-rotational (spec §11.1): ℓ = |L n + Δu|, m = (L n + Δu)/ℓ, N = k(ℓ − L) + N0,
  /// f = N[−m; m], K_T = k blk(mmᵀ) + (N/ℓ) blk(I − mmᵀ) (Crisfield vol. 1 §3.1).
  Corotational,
};

/// Reference geometry: unit direction n (I→J) and length L (L = 0 only for 1-D springs).
struct AxialMember {
  Eigen::VectorXd n;
  double length = 0.0;
  int dim() const { return static_cast<int>(n.size()); }
};

/// Axial state at one displacement.
struct AxialState {
  double force = 0.0;           ///< N, tension positive
  double extension = 0.0;       ///< e such that N = k e + N0 (ℓ − L when co-rotational)
  double current_length = 0.0;  ///< |L n + Δu|, the geometric current length
};

/// Adds s·blk(A) to K (2d×2d).
inline void add_block(const Eigen::MatrixXd& A, double s, Eigen::MatrixXd& K) {
  const auto d = A.rows();
  K.topLeftCorner(d, d) += s * A;
  K.bottomRightCorner(d, d) += s * A;
  K.topRightCorner(d, d) -= s * A;
  K.bottomLeftCorner(d, d) -= s * A;
}

/// Axial force, internal force f (2d) and tangent K (2d×2d) for displacement u (2d), axial
/// stiffness k (EA/L for a spar, K for a spring) and force at zero extension N0 (EA·ISTRN).
/// Throws ElementSolutionError when a co-rotational member collapses to zero length.
inline AxialState axial_response(const AxialMember& m, AxialKinematics kin, double k, double n0,
                                 const Eigen::VectorXd& u, Eigen::MatrixXd& K, Eigen::VectorXd& f,
                                 int element_id) {
  const int d = m.dim();
  const Eigen::VectorXd du = u.tail(d) - u.head(d);
  const Eigen::VectorXd chord = m.length * m.n + du;
  AxialState s;
  s.current_length = chord.norm();
  K.setZero(2 * d, 2 * d);
  f.setZero(2 * d);
  const Eigen::MatrixXd I = Eigen::MatrixXd::Identity(d, d);
  Eigen::VectorXd g;  // direction of the internal force at node J
  switch (kin) {
    case AxialKinematics::Linear: {
      s.extension = m.n.dot(du);
      s.force = k * s.extension + n0;
      g = m.n;
      add_block(m.n * m.n.transpose(), k, K);
      break;
    }
    case AxialKinematics::StressStiffened: {
      const Eigen::MatrixXd P = I - m.n * m.n.transpose();
      const Eigen::VectorXd w = P * du;
      s.extension = m.n.dot(du) + w.squaredNorm() / (2.0 * m.length);
      s.force = k * s.extension + n0;
      g = m.n + w / m.length;
      add_block(g * g.transpose(), k, K);
      add_block(P, s.force / m.length, K);
      break;
    }
    case AxialKinematics::Corotational: {
      const double ell = s.current_length;
      if (!(ell > 1e-12 * std::max(m.length, 1.0)))
        throw ElementSolutionError(
            element_id, fmt::format("element {} collapsed to zero length under large deflection "
                                    "(its nodes met); use a smaller time step (DELTIM) or more "
                                    "substeps (NSUBST), or check the loads",
                                    element_id));
      g = chord / ell;
      s.extension = ell - m.length;
      s.force = k * s.extension + n0;
      add_block(g * g.transpose(), k, K);
      add_block(I - g * g.transpose(), s.force / ell, K);
      break;
    }
  }
  f.head(d) = -s.force * g;
  f.tail(d) = s.force * g;
  return s;
}

}  // namespace impactfe::corotational
