#pragma once
/// The co-rotational kinematics of a flat 3-node shell facet worked out in the facet's own frame:
/// the fast path of Shell4 for elastic triangles under large deflection (issue 11).
///
/// It is the same formulation as Shell4's element-independent path (shell_frame.h, so3.h;
/// Nour-Omid & Rankin 1991, Felippa & Haugen 2005): f = Bᵀ K̄ d and the consistent tangent
/// Bᵀ K̄ B + ∂(Bᵀ)/∂u·(K̄ d). For a triangle the frame has a closed form (e1 along side 0→1,
/// e3 the normal), and in that frame its spin δω = G δx reads (Felippa & Haugen 2005, §5.4)
///     δω̂1 = Σ_b c1_b δẑ_b,  δω̂2 = Σ_b c2_b δẑ_b,  δω̂3 = Σ_b c3_b δŷ_b,
///     c1 = [b1 − L, −b1, L] / (L b2),  c2 = [1, −1, 0] / L,  c3 = [−1, 1, 0] / L,
/// with the corners at (0, 0), (L, 0), (b1, b2) of the frame. The out-of-plane deformational
/// translations vanish identically (three points span their plane), and the flat kernel's
/// membrane (u, v, θz) and bending (w, θx, θy) DOFs are uncoupled: B and K̄ are mostly zeros,
/// which the products here skip. Everything is formed in the frame and rotated to global axes
/// once: about a fifth of the general path's operations.
#include <Eigen/Core>
#include <Eigen/Geometry>

#include <array>
#include <memory>

namespace impactfe {

class CorotationalTriangle {
 public:
  using Vec3 = Eigen::Vector3d;
  using Mat3 = Eigen::Matrix3d;
  using Vec18 = Eigen::Matrix<double, 18, 1>;
  using Mat18 = Eigen::Matrix<double, 18, 18>;

  /// X: initial corners; R0, c0: initial frame and centroid (shell_frame of X); K_local: the
  /// 18 × 18 flat-kernel stiffness, local DOFs u v w θx θy θz per corner.
  CorotationalTriangle(const std::array<Vec3, 3>& X, const Mat3& R0, const Vec3& c0,
                       const Eigen::MatrixXd& K_local);
  ~CorotationalTriangle();

  /// True when K_local couples no membrane DOF (u, v, θz) with a bending one (w, θx, θy), as
  /// the elastic flat kernel never does; the fast path relies on it.
  static bool uncoupled(const Eigen::MatrixXd& K_local);

  /// Internal force at the total displacement u (18: UX UY UZ ROTX ROTY ROTZ per corner).
  void internal_force(const Eigen::VectorXd& u, Eigen::VectorXd& f) const;
  /// Consistent tangent and internal force at u.
  void tangent(const Eigen::VectorXd& u, Eigen::MatrixXd& K, Eigen::VectorXd& f) const;
  /// The deformational displacement d(u) in the flat kernel's local DOFs (w = 0): what its
  /// stresses are recovered from.
  Eigen::VectorXd deformation(const Eigen::VectorXd& u) const;

 private:
  struct State;
  using Mat16x18 = Eigen::Matrix<double, 16, 18>;
  using Mat24x18 = Eigen::Matrix<double, 24, 18>;
  // The consistent tangent in four parts (tangent): the variation B̂ of the deformation in the
  // frame, the material part B̂ᵀ K̄ B̂, the geometric part (the frame's and the rotations'
  // variations at fixed local forces), and the transformation to global axes.
  static Mat16x18 frame_variation(const State& s);
  Mat24x18 material_part(const Mat16x18& B) const;
  static void add_geometric_part(const State& s, const Mat16x18& B, Mat24x18& Kl);
  static void to_global(const State& s, const Mat24x18& Kl, Eigen::MatrixXd& K, Eigen::VectorXd& f);
  void corotate(const Eigen::VectorXd& u, State& s) const;
  /// Local forces n̂, M̂ (frame components), ŵ and the frame-component internal force f̂.
  void local_forces(State& s) const;
  /// The co-rotated state at u, with its local forces when asked for: the last one evaluated
  /// when u is bitwise the same, else formed anew. A Newton iteration evaluates the internal
  /// force at an iterate and then the tangent at the same iterate, and a stored point the
  /// stresses at the converged iterate whose residual was evaluated last: the corotation (two
  /// SO(3) maps per corner) was a quarter of the thesis helmet's run (issue 11). The assembler
  /// evaluates an element on one thread at a time, so the memo needs no lock.
  const State& state_at(const Eigen::VectorXd& u, bool with_forces) const;

  std::array<Vec3, 3> X_;
  Eigen::Quaterniond q0_;                 // the initial frame R0 as a unit quaternion
  std::array<double, 3> xi0_{}, eta0_{};  // initial corners in the initial frame, from c0
  // The kernel's stiffness split: membrane on (u, v, θz) and bending on (θx, θy) per corner
  // (the w rows and columns meet only the deformational w, which is zero).
  Eigen::Matrix<double, 9, 9> K_membrane_;
  Eigen::Matrix<double, 6, 6> K_bending_;
  // Both, over u v θx θy θz per corner (the tangent's order), padded with a zero 16th row and
  // column: a 16-vector is whole SIMD packets, where Eigen takes a fixed 15-vector two doubles
  // at a time (corotational_triangle.cpp, tangent).
  Eigen::Matrix<double, 16, 16> K16_;
  // The memo of state_at: the last u and its state (forces formed or not).
  mutable std::unique_ptr<State> last_;
  mutable Vec18 last_u_;
  mutable bool last_has_forces_ = false;
};

}  // namespace impactfe
