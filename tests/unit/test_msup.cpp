// Mode-superposition transient on matrices, through the same pieces the MSUP driver uses
// (lowest_eigenpairs + ReducedDynamics with modal matrices and GP gaps as modal forces):
// a free-free bar hit by a step force against the 1-D wave solution, and a two-mass spring
// system with a gap under MSUP (all modes) against the physical-coordinate integration.
#include <gtest/gtest.h>

#include <Eigen/Eigenvalues>
#include <cmath>

#include "analysis/structure.h"
#include "linalg/eigen_solver.h"
#include "reduction/reduced_dynamics.h"

namespace test_msup {

using namespace impactfe;

namespace {

constexpr double kE = 30e6, kRho = 0.00073, kL = 10.0;

/// Free-free LINK1 bar of n elements along x (A = 1), lumped mass; UY constrained.
struct Bar {
  Model model;
  std::unique_ptr<Structure> structure;
  std::unique_ptr<DofMap> dofs;
  std::unique_ptr<Assembler> assembler;
  SparseMatrix k_lower, m_lower;
  explicit Bar(int n) {
    for (int i = 0; i <= n; ++i) model.nodes[i + 1] = Node{i + 1, Vec3(kL * i / n, 0, 0)};
    ElementType et;
    et.id = 1;
    et.ansys_name = "LINK1";
    model.element_types[1] = et;
    model.real_sets[1] = RealSet{1, {1.0}};
    Material mat;
    mat.id = 1;
    mat.props = {{"EX", kE}, {"DENS", kRho}};
    model.materials[1] = mat;
    for (int e = 1; e <= n; ++e) {
      ElementRecord r;
      r.id = e;
      r.nodes = {e, e + 1};
      model.elements[e] = r;
    }
    AnalysisOptions o;
    o.lumped_mass = true;
    structure = std::make_unique<Structure>(model, o, RunSettings{});
    std::set<DofKey> uy;
    for (int i = 1; i <= n + 1; ++i) uy.insert({i, Dof::UY});
    dofs = std::make_unique<DofMap>(structure->elements(), uy);
    assembler = std::make_unique<Assembler>(structure->elements(), *dofs, structure->context());
    const VectorXd zero = VectorXd::Zero(dofs->n_active());
    k_lower.resize(dofs->n_free(), dofs->n_free());
    m_lower.resize(dofs->n_free(), dofs->n_free());
    assembler->assemble({1, 0, 0}, zero, zero, Assembler::Output{&k_lower, nullptr, nullptr});
    assembler->assemble({0, 0, 1}, zero, zero, Assembler::Output{&m_lower, nullptr, nullptr});
  }
  int ux(int node) const { return dofs->index({node, Dof::UX}); }
};

}  // namespace

TEST(Msup, FreeFreeBarStepForceFollowsTheWaveSolution) {
  // Step force F at x = L on a free-free bar: the loaded end moves at v = F / (rho A c) until
  // the reflected wave returns (t < 2L/c); the far end stays at rest until t = L/c; the centre
  // of mass follows F t² / (2 m) exactly.
  const int n = 50;
  Bar bar(n);
  const int nf = bar.dofs->n_free();
  // Enough modes: all of them (dense solve; the Lanczos path returns a leading subset).
  const MatrixXd kd = MatrixXd(SparseMatrix(bar.k_lower.selfadjointView<Eigen::Lower>()));
  const MatrixXd md = MatrixXd(SparseMatrix(bar.m_lower.selfadjointView<Eigen::Lower>()));
  Eigen::GeneralizedSelfAdjointEigenSolver<MatrixXd> eig(kd, md);
  const int nm = nf;
  const MatrixXd phi = eig.eigenvectors();
  MatrixXd km = MatrixXd::Zero(nm, nm);
  km.diagonal() = eig.eigenvalues().cwiseMax(0.0);
  // The Lanczos solver the driver uses finds the same lowest frequencies.
  const EigenResult lanczos = lowest_eigenpairs(bar.k_lower, bar.m_lower, 8, -1.0);
  for (int j = 1; j < std::min<int>(8, lanczos.eigenvalues.size()); ++j)
    EXPECT_NEAR(lanczos.eigenvalues(j), eig.eigenvalues()(j), 1e-6 * eig.eigenvalues()(j));
  const double c = std::sqrt(kE / kRho), f = 100.0, t_wave = kL / c;
  const double h = t_wave / 400.0;
  ReducedDynamics d(km, MatrixXd::Identity(nm, nm), MatrixXd(), {},
                    make_time_integrator(AnalysisOptions{}));
  d.start(VectorXd::Zero(nm), VectorXd::Zero(nm), VectorXd::Zero(nm), h);
  VectorXd load = VectorXd::Zero(nf);
  load(bar.ux(n + 1)) = f;
  const VectorXd fq = phi.transpose() * load;
  const int steps = static_cast<int>(std::lround(0.9 * t_wave / h));
  for (int s = 1; s <= steps; ++s) d.step(fq);
  const double t = steps * h;
  const VectorXd u = phi * d.q();
  const double tip = u(bar.ux(n + 1)), far = u(bar.ux(1));
  EXPECT_NEAR(tip, f * t / (kRho * c), 0.05 * f * t / (kRho * c));
  EXPECT_LT(std::abs(far), 0.02 * tip);
  const SparseMatrix m_full = bar.m_lower.selfadjointView<Eigen::Lower>();
  const double mass = kRho * kL;
  const double mean = (m_full * u).sum() / mass;
  EXPECT_NEAR(mean, f * t * t / (2.0 * mass), 0.01 * f * t * t / (2.0 * mass));
}

TEST(Msup, TwoMassGapAllModesEqualsPhysicalIntegration) {
  // m1 -k- m2, m2 moving toward a grounded gap: MSUP with both modes and the GP force applied
  // as a modal force reproduces the physical-coordinate integration (same Newmark steps).
  MatrixXd k(2, 2), m(2, 2);
  const double ks = 4e3;
  k << ks, -ks, -ks, ks;
  m << 0.2, 0, 0, 0.3;
  Eigen::GeneralizedSelfAdjointEigenSolver<MatrixXd> es(k, m);
  const MatrixXd phi = es.eigenvectors();  // mass-normalised
  MatrixXd km = MatrixXd::Zero(2, 2);
  km.diagonal() = es.eigenvalues().cwiseMax(0.0);
  GeneralizedGap phys, modal;
  phys.b_j = VectorXd::Unit(2, 1);
  modal.b_j = phi.row(1).transpose();
  phys.stiffness = modal.stiffness = 2e4;
  phys.gap = modal.gap = 0.02;
  const double h = 2e-4;
  ReducedDynamics p(k, m, MatrixXd(), {phys}, make_time_integrator(AnalysisOptions{}));
  ReducedDynamics q(km, MatrixXd::Identity(2, 2), MatrixXd(), {modal},
                    make_time_integrator(AnalysisOptions{}));
  const VectorXd v0 = VectorXd::Constant(2, -5.0);
  p.start(VectorXd::Zero(2), v0, VectorXd::Zero(2), h);
  q.start(VectorXd::Zero(2), phi.transpose() * m * v0, VectorXd::Zero(2), h);
  double peak = 0.0, diff = 0.0, umax = 0.0;
  for (int s = 0; s < 200; ++s) {
    p.step(VectorXd::Zero(2));
    q.step(VectorXd::Zero(2));
    diff = std::max(diff, (phi * q.q() - p.q()).cwiseAbs().maxCoeff());
    umax = std::max(umax, p.q().cwiseAbs().maxCoeff());
    peak = std::min(peak, p.gap_forces()(0));
    EXPECT_NEAR(q.gap_forces()(0), p.gap_forces()(0), 1e-8 * 2e4 * 0.02) << s;
  }
  EXPECT_LT(peak, 0.0);  // the gap closed
  EXPECT_LT(diff, 1e-9 * umax);
}

}  // namespace test_msup
