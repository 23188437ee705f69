#pragma once
/// Rigid bodies of explicit dynamics (EDMP,RIGID; docs/explicit_dynamics.md, "Rigid bodies"):
/// the nodes of a rigid material's elements move as one body, x_i = c + R r_i with c the centre
/// of mass, R the rotation and r_i the node's offset from the centre at the start. The body
/// takes the forces of its nodes (elements sharing them, contact, ACEL, loads by curve) and
/// moves by Newton–Euler (Goldstein, Classical Mechanics, §5.5):
///   M a_c = Σ F_i,   J α + ω × J ω = Σ r_i × F_i,   J = R J₀ Rᵀ,
/// J₀ = ∫ρ (|r|² 1 − r rᵀ) dV about the centre, integrated over the body's elements (lumped
/// point masses would give a one-brick cube three times its inertia).
#include <Eigen/Dense>

#include <array>
#include <cstddef>
#include <vector>

namespace impactfe {

struct RigidBody {
  int material = 0;                      // the body's (EDCRB: the master part's) material
  std::vector<int> materials;            // every material whose elements it holds, ascending
  std::vector<std::size_t> nodes;        // system node indices, ascending
  std::vector<Eigen::Vector3d> offsets;  // r_i at the start, per node
  double mass = 0.0;
  Eigen::Vector3d centre0 = Eigen::Vector3d::Zero();
  Eigen::Matrix3d inertia0 = Eigen::Matrix3d::Zero();  // J₀ about the centre, global axes
  std::array<bool, 3> fixed_translation{}, fixed_rotation{};
};

/// The axes a constraint code of EDMP,RIGID fixes (0 none, 1 x, 2 y, 3 z, 4 x y, 5 y z, 6 z x,
/// 7 all).
std::array<bool, 3> rigid_constraint_axes(int code);

/// Mass, centre and J₀ of a body from the lumped masses and initial coordinates of its nodes
/// (the row-sum masses keep the first moment exactly) and its second moment S = ∫ρ x xᵀ dV
/// about the origin: J₀ = tr(S_c) 1 − S_c with S_c = S − M c cᵀ (parallel axes).
void set_rigid_body_inertia(RigidBody& body, const std::vector<double>& mass,
                            const std::vector<double>& x0, const std::vector<double>& y0,
                            const std::vector<double>& z0, const Eigen::Matrix3d& second_moment);

/// The angular acceleration α of J α = m about the free axes (α = 0 about the fixed ones). A
/// direction without inertia (the axis of a body whose nodes lie on a line) gets no
/// acceleration: no node of the body moves by it.
Eigen::Vector3d rigid_angular_acceleration(const Eigen::Matrix3d& inertia,
                                           const Eigen::Vector3d& moment,
                                           const std::array<bool, 3>& fixed);

}  // namespace impactfe
