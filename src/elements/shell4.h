#pragma once
/// SHELL63 (and SHELL181 for linear elastic use): 4-node elastic flat-facet shell, or the
/// triangle it becomes when K = L. Six DOFs per node in global axes. See docs/elements/shell63.md.
///
/// Small deflection: K = Aᵀ K_l A with A = (warping rigid links) · (global → element axes) and
/// K_l from shell::FlatShellKernel. Large deflection: element-independent co-rotational
/// formulation (Rankin & Nour-Omid 1988; Felippa & Haugen 2005), see tangent().
#include <Eigen/Core>

#include <memory>
#include <string>
#include <vector>

#include "elements/corotational_triangle.h"
#include "elements/element.h"
#include "elements/shell_kernel.h"

namespace impactfe {

/// Everything make_shell4 reads from the model, resolved; also lets tests build elements
/// without a deck.
struct Shell4Data {
  std::vector<int> node_ids;    // 3 or 4 distinct nodes
  std::vector<Vec3> positions;  // initial coordinates, same order
  shell::KernelData kernel;     // material, thickness, options
  double theta_deg = 0.0;       // THETA: result axes rotated about the normal
  bool shell181 = false;
  /// SHELL181 with a TB plasticity table: layered J2 plasticity (shell_kernel.h).
  std::optional<J2Plasticity> plasticity;
  /// Built for large deflection (ElementBuildContext::large_deflection): keep the co-rotational
  /// local stiffness K̄, which every iteration reads; otherwise it is formed when asked.
  bool keep_corotational_stiffness = false;
};

class Shell4 : public Element {
 public:
  /// Throws InputError(where, ...) for zero area or a re-entrant quad.
  Shell4(int id, const Shell4Data& data, const SourceLocation& where);

  /// "Shell4", or "Shell4Layered" for a layered SHELL181 section (its results add the layers').
  const char* family() const override { return laminate_ ? "Shell4Layered" : "Shell4"; }
  /// The result names of a layered SHELL181: the homogeneous ones, then for each layer L:
  /// SX SY SXY SEQV at its TOP, MID and BOT ("SX_L1_TOP"), up to kMaxResultLayers layers.
  static const std::vector<std::string>& layered_names();
  /// The result names of a homogeneous element.
  static const std::vector<std::string>& names();
  static constexpr int kMaxResultLayers = 12;
  const std::vector<DofKey>& dofs() const override { return dofs_; }
  bool is_nonlinear(const ElementContext& ctx) const override {
    return ctx.large_deflection || ctx.stress_stiffening || plasticity_.has_value();
  }
  bool has_history() const override { return plasticity_.has_value(); }
  double plastic_work() const override;
  void commit_history(const ElementContext& ctx, const Eigen::VectorXd& u) override;
  std::vector<double> history_state() const override;
  void restore_history_state(const std::vector<double>& state) override;
  /// Small deflection: K = K_lin (+ stress stiffness Aᵀ K_g(σ(u)) A with SSTIF), f = K u.
  /// Large deflection: co-rotational f = Bᵀ K̄ d(u), K = Bᵀ K̄ B + ∂Bᵀ/∂u·(K̄ d), with
  /// B = ∂d/∂u and the geometric part ∂Bᵀ/∂u·f_l both analytic (shell_frame.h, so3.h).
  void tangent(const ElementContext& ctx, const Eigen::VectorXd& u, Eigen::MatrixXd& K,
               Eigen::VectorXd& f_int) const override;
  /// f_int of tangent() alone (large deflection: Bᵀ K̄ d, no stiffness products).
  void internal_force(const ElementContext& ctx, const Eigen::VectorXd& u,
                      Eigen::VectorXd& f_int) const override;
  bool separate_internal_force(const ElementContext& ctx) const override {
    return ctx.large_deflection && !plasticity_;
  }
  void mass(const ElementContext& ctx, Eigen::MatrixXd& M) const override;
  /// Pressure on face 1 (bottom: positive pushes along +N, the I-J-K-L normal) or face 2 (top:
  /// along −N); consistent loads on the translations, on the face deformed by u under large
  /// deflection. In-plane edge faces 3..6 are not supported (ModelError).
  void pressure_load(const ElementContext& ctx, int face, const std::array<double, 4>& p,
                     const Eigen::VectorXd& u, Eigen::VectorXd& f) const override;
  const std::vector<std::string>& result_names() const override;
  /// Centroidal resultants and stresses in element axes (rotated by THETA); see result_names.
  void results(const ElementContext& ctx, const Eigen::VectorXd& u, const Eigen::VectorXd& v,
               ElementResultValues& out) const override;

  /// The element axes of results(): the facet frame (e1 along I-J projected on the mean plane,
  /// e3 the normal) rotated by THETA about e3; under large deflection the co-rotated frame at u.
  Eigen::Matrix3d result_axes(const ElementContext& ctx, const Eigen::VectorXd& u) const override;
  /// Deformational local displacement d(u) (element axes, before the warping links) and, when
  /// B != nullptr, its derivative B = ∂d/∂u (co-rotational kinematics). Exposed for tests.
  void corotational_kinematics(const Eigen::VectorXd& u, Eigen::VectorXd& d,
                               Eigen::MatrixXd* B) const;
  /// ∫t dA of the facet.
  std::optional<double> volume() const override { return kernel_->volume(); }
  /// Geometric stiffness K_G = ∂(B(u)ᵀ f_l)/∂u at a fixed local force vector f_l (6n), the part
  /// of the large-deflection tangent beyond Bᵀ K̄ B. Exposed for tests.
  void corotational_geometric_stiffness(const Eigen::VectorXd& u, const Eigen::VectorXd& f_l,
                                        Eigen::MatrixXd& K_G) const;
  /// The element-independent co-rotational tangent and force (the quadrilaterals' path) also
  /// for a triangle, which tangent() otherwise takes through CorotationalTriangle. For tests.
  void corotational_tangent_general(const Eigen::VectorXd& u, Eigen::MatrixXd& K,
                                    Eigen::VectorXd& f_int) const;
  /// True when tangent() and internal_force() take the triangle's fast path under large
  /// deflection (an elastic triangle).
  bool fast_triangle() const { return triangle_ != nullptr; }
  const shell::FlatShellKernel& kernel() const { return *kernel_; }
  int n_nodes() const { return n_; }

 private:
  Eigen::VectorXd local_displacement(const ElementContext& ctx, const Eigen::VectorXd& u) const;
  /// Elastic-plastic tangent and force (small deflection, or co-rotational on the local
  /// response); `updated`, `mean`, `layers` as in FlatShellKernel::plastic_response.
  void plastic_tangent(
      const ElementContext& ctx, const Eigen::VectorXd& u, Eigen::MatrixXd& K,
      Eigen::VectorXd& f_int, std::vector<PlasticState>* updated, shell::Resultants* mean = nullptr,
      std::array<Eigen::Vector3d, shell::FlatShellKernel::kLayers>* layers = nullptr) const;

  int n_ = 0;
  std::vector<DofKey> dofs_;
  std::vector<Vec3> X_;
  Eigen::Matrix3d R0_;
  Vec3 c0_ = Vec3::Zero();
  /// W: the rigid links corner → mean plane in local axes (6n × 6n; the identity but for the
  /// warping offsets h), and A = W · (global → local). Both are formed when used rather than
  /// kept, as are Aᵀ K_l A and Aᵀ M_l A: a large model holds thousands of shells, and these
  /// 24 × 24 matrices were most of its memory (docs/benchmarks.md, stop 25).
  Eigen::MatrixXd rigid_links() const;
  Eigen::MatrixXd to_local() const;
  /// W d and A u corner by corner, without forming W or A: the results of every stored point
  /// need only these products (issue 11: forming A was a 24³ product per shell and point, 15 %
  /// of the 25 600-shell dome's run).
  Eigen::VectorXd apply_rigid_links(Eigen::VectorXd d) const;
  Eigen::VectorXd apply_to_local(const Eigen::VectorXd& u) const;
  /// K̄ = Wᵀ K_l W, the co-rotational local stiffness (K_l itself for a flat element): the kept
  /// one, else formed into `scratch`.
  const Eigen::MatrixXd& corotational_stiffness(Eigen::MatrixXd& scratch) const;
  Eigen::MatrixXd form_corotational_stiffness() const;

  std::vector<double> h_;  // warping offsets of the corners from the mean plane
  /// K̄ kept for large deflection (the elastic triangle's fast path keeps its own), empty
  /// otherwise. Kept always, with the kernel's K_l, M_l and drilling matrix (now formed when
  /// asked), these 24 × 24 matrices held 471 MB on the 25 600-shell dome (benchmarks.md, stop 27).
  Eigen::MatrixXd K_bar_;
  double theta_ = 0.0;  // rad
  std::unique_ptr<shell::FlatShellKernel> kernel_;
  std::unique_ptr<CorotationalTriangle> triangle_;  // elastic triangle: the fast path
  std::optional<J2Plasticity> plasticity_;
  std::shared_ptr<const shell::Laminate> laminate_;  // a layered section (KernelData::laminate)
  std::vector<PlasticState> committed_;              // in-plane point × layer
};

}  // namespace impactfe
