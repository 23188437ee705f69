#include "linalg/schur_solver.h"

#include <cholmod.h>
#include <fmt/format.h>

#include <Eigen/Cholesky>
#include <Eigen/Dense>
#include <memory>
#include <new>
#include <stdexcept>

#include "core/errors.h"
#include "linalg/solver_support.h"

namespace impactfe {

namespace {

using solver_support::cholmod_lower_view;
using solver_support::ScopedTimer;

/// CHOLMOD supernodal P A Pᵀ = L Lᵀ with the unknowns of c last (in their order):
///   L = [L_ii 0; L_ci L_cc],  A_ii = L_ii L_iiᵀ,  A_ic = L_ii L_ciᵀ,
/// so S = A_cc − A_ci A_ii⁻¹ A_ic = L_cc L_ccᵀ (the factorization stopped before c is Gaussian
/// elimination of i, i.e. static condensation; Bathe, Finite Element Procedures, §8.2.4). With
/// z = L⁻¹ P r:  y = (A⁻¹ r)_c = L_cc⁻ᵀ z_c, and the back substitution Lᵀ x = z with z_c
/// replaced by L_ccᵀ x_c gives x_c on c and x_i = L_ii⁻ᵀ (z_i − L_ciᵀ x_c) = A_ii⁻¹ (r_i − A_ic
/// x_c). Nothing of size n × m is formed: a step costs one forward and one back substitution.
///
/// The ordering: CHOLMOD's own choice (AMD or METIS) for A_ii, then c. Ordering c last is
/// ordering it as a final separator; for the contact surfaces of a body (the nonlinear
/// elements' DOFs) the fill stays close to the unconstrained ordering's.
class CholmodSchurSolver final : public SchurSolver {
  struct FreeSparse {
    cholmod_common* common;
    void operator()(cholmod_sparse* s) const { cholmod_free_sparse(&s, common); }
  };

 public:
  CholmodSchurSolver(int n, std::vector<int> c) : SchurSolver(std::move(c)), n_(n) {
    cholmod_start(&common_);
    common_.print = 0;
    common_.error_handler = nullptr;
    common_.supernodal = CHOLMOD_SUPERNODAL;  // L_cc is read from the supernodes
    common_.final_ll = 1;
    common_.quick_return_if_not_posdef = 1;
  }
  ~CholmodSchurSolver() override {
    if (factor_) cholmod_free_factor(&factor_, &common_);
    cholmod_finish(&common_);
  }
  CholmodSchurSolver(const CholmodSchurSolver&) = delete;
  CholmodSchurSolver& operator=(const CholmodSchurSolver&) = delete;

  std::string name() const override { return "CHOLMOD, condensed set ordered last"; }

  void analyze_pattern(const SparseMatrix& lower) override {
    ScopedTimer timer(counters_.analyze_seconds);
    IMPACTFE_CHECK(lower.rows() == n_ && lower.cols() == n_, "SchurSolver: matrix size");
    if (factor_) cholmod_free_factor(&factor_, &common_);
    const int m = static_cast<int>(c_.size());
    const int ni = n_ - m;
    // The pattern of A_ii (lower triangle) and its fill-reducing ordering.
    std::vector<int> rest, local(static_cast<std::size_t>(n_), 0);
    rest.reserve(static_cast<std::size_t>(ni));
    for (int k : c_) local[static_cast<std::size_t>(k)] = -1;
    for (int j = 0; j < n_; ++j)
      if (local[static_cast<std::size_t>(j)] == 0) {
        local[static_cast<std::size_t>(j)] = static_cast<int>(rest.size());
        rest.push_back(j);
      }
    std::vector<int> column_start{0}, row_index;
    row_index.reserve(static_cast<std::size_t>(lower.nonZeros()));
    for (int j : rest) {
      for (SparseMatrix::InnerIterator it(lower, j); it; ++it)
        if (const int r = local[static_cast<std::size_t>(it.row())]; r >= 0) row_index.push_back(r);
      column_start.push_back(static_cast<int>(row_index.size()));
    }
    cholmod_sparse a_ii = cholmod_lower_view(static_cast<std::size_t>(ni), row_index.size(),
                                             column_start.data(), row_index.data(), nullptr);
    cholmod_factor* ordering = cholmod_analyze(&a_ii, &common_);
    check_analysis(ordering);
    std::vector<int> perm(static_cast<std::size_t>(n_));
    const auto* perm_ii = static_cast<const int*>(ordering->Perm);
    for (int k = 0; k < ni; ++k)
      perm[static_cast<std::size_t>(k)] = rest[static_cast<std::size_t>(perm_ii[k])];
    cholmod_free_factor(&ordering, &common_);
    for (int k = 0; k < m; ++k)
      perm[static_cast<std::size_t>(ni + k)] = c_[static_cast<std::size_t>(k)];

    // The whole matrix in that order, as given: postordering its elimination tree could move
    // columns of i behind columns of c when c is not connected through its own block.
    common_.nmethods = 1;
    common_.method[0].ordering = CHOLMOD_GIVEN;
    common_.postorder = 0;
    cholmod_sparse a = cholmod_lower_view(lower);
    factor_ = cholmod_analyze_p(&a, perm.data(), nullptr, 0, &common_);
    common_.nmethods = 0;
    common_.postorder = 1;
    check_analysis(factor_);
    solver_support::require_blas_for(factor_);
    const auto* used = static_cast<const int*>(factor_->Perm);
    for (int k = 0; k < n_; ++k)
      IMPACTFE_CHECK(used[k] == perm[static_cast<std::size_t>(k)],
                     "SchurSolver: CHOLMOD changed the given ordering");
    ++counters_.analyses;
  }

  void factorize(const SparseMatrix& lower) override { factor(lower, nullptr); }
  void factorize_and_release(SparseMatrix& lower) override { factor(lower, &lower); }

  VectorXd condense(const Eigen::Ref<const VectorXd>& r) override {
    IMPACTFE_CHECK(factor_ != nullptr && r.size() == n_, "SchurSolver: condense before factorize");
    ScopedTimer timer(counters_.solve_seconds);
    const auto* perm = static_cast<const int*>(factor_->Perm);
    z_.resize(n_);
    for (int k = 0; k < n_; ++k) z_(k) = r(perm[k]);
    substitute(CHOLMOD_L, z_);
    const auto m = static_cast<Eigen::Index>(c_.size());
    return l_cc_.triangularView<Eigen::Lower>().transpose().solve(z_.tail(m));
  }

  void recover(const VectorXd& x_c, VectorXd& x) override {
    const auto m = static_cast<Eigen::Index>(c_.size());
    IMPACTFE_CHECK(z_.size() == n_ && x_c.size() == m, "SchurSolver: recover before condense");
    ScopedTimer timer(counters_.solve_seconds);
    back_ = z_;  // z_ stays for another recover of the same condense
    back_.tail(m) = l_cc_.triangularView<Eigen::Lower>().transpose() * x_c;
    substitute(CHOLMOD_Lt, back_);
    const auto* perm = static_cast<const int*>(factor_->Perm);
    x.resize(n_);
    for (int k = 0; k < n_; ++k) x(perm[k]) = back_(k);
    for (Eigen::Index k = 0; k < m; ++k) x(c_[static_cast<std::size_t>(k)]) = x_c(k);
    ++counters_.solves;
  }

 private:
  void check_analysis(const cholmod_factor* f) const {
    if (f) return;
    if (common_.status == CHOLMOD_OUT_OF_MEMORY) throw std::bad_alloc();
    throw std::runtime_error(fmt::format(
        "the sparse solver's symbolic analysis failed (CHOLMOD status {})", common_.status));
  }

  /// Numeric factorization of `lower` (freed into `release` when given), then S = L_cc L_ccᵀ.
  /// What cholmod_factorize does for a supernodal factor with a given ordering, in steps:
  /// CHOLMOD's supernodal kernel reads the lower triangle of P A Pᵀ, formed by two transposes
  /// (the first permutes into the upper triangle); A itself is not needed after that, and the
  /// caller's copy is freed before the factor's values are allocated.
  void factor(const SparseMatrix& lower, SparseMatrix* release) {
    if (!factor_) analyze_pattern(lower);
    ScopedTimer timer(counters_.factorize_seconds);
    counters_.matrix_nonzeros = static_cast<long>(lower.nonZeros());
    cholmod_sparse a = cholmod_lower_view(lower);
    cholmod_sparse* upper =
        cholmod_ptranspose(&a, 2, static_cast<int*>(factor_->Perm), nullptr, 0, &common_);
    if (!upper) throw std::bad_alloc();
    cholmod_sparse* permuted = cholmod_ptranspose(upper, 2, nullptr, nullptr, 0, &common_);
    cholmod_free_sparse(&upper, &common_);
    if (!permuted) throw std::bad_alloc();
    const std::unique_ptr<cholmod_sparse, FreeSparse> owned(permuted, FreeSparse{&common_});
    // Swapped out: Eigen's assignment of an empty matrix would keep the storage.
    if (release) SparseMatrix().swap(*release);
    double beta[2] = {0.0, 0.0};
    cholmod_super_numeric(permuted, nullptr, beta, factor_, &common_);
    ++counters_.factorizations;
    if (common_.status == CHOLMOD_OUT_OF_MEMORY) throw std::bad_alloc();
    const auto* perm = static_cast<const int*>(factor_->Perm);
    // The weakest pivot of P A Pᵀ, as a row of A.
    const auto weakest_row = [&] {
      const SparseMatrix pap = Eigen::Map<const SparseMatrix>(
          n_, n_, static_cast<Eigen::Index>(cholmod_nnz(permuted, &common_)),
          static_cast<const int*>(permuted->p), static_cast<const int*>(permuted->i),
          static_cast<const double*>(permuted->x));
      const int row = weakest_pivot_row(pap);
      return row >= 0 ? perm[row] : row;
    };
    if (common_.status == CHOLMOD_NOT_POSDEF || factor_->minor < factor_->n) {
      const int row = factor_->minor < factor_->n ? perm[factor_->minor] : weakest_row();
      throw SingularMatrixError(row, "the matrix to condense is not positive definite");
    }
    // rcond is (min L_jj / max L_jj)^2: only a near-mechanism gets below 1e-13; then diagnose.
    if (cholmod_rcond(factor_, &common_) < 1e-13)
      if (const int row = weakest_row(); row >= 0)
        throw SingularMatrixError(row, "near-zero pivot in the factorization");
    read_trailing_block();
    substitution_.plan(solver_support::supernodal_layout(factor_));
    const auto m = static_cast<Eigen::Index>(c_.size());
    MatrixXd lower_schur = MatrixXd::Zero(m, m);
    lower_schur.selfadjointView<Eigen::Lower>().rankUpdate(l_cc_);
    schur_ = lower_schur.selfadjointView<Eigen::Lower>();
    counters_.factor_nonzeros = static_cast<long>(common_.lnz);
    counters_.factor_bytes =
        static_cast<long>(factor_->xsize * sizeof(double) + factor_->ssize * sizeof(int));
  }

  /// L_cc: the last m columns of the supernodal L, rows n − m and below.
  void read_trailing_block() {
    const int m = static_cast<int>(c_.size());
    const int first = n_ - m;
    const auto* super = static_cast<const int*>(factor_->super);
    const auto* pi = static_cast<const int*>(factor_->pi);
    const auto* px = static_cast<const int*>(factor_->px);
    const auto* s = static_cast<const int*>(factor_->s);
    const auto* x = static_cast<const double*>(factor_->x);
    l_cc_ = MatrixXd::Zero(m, m);
    for (size_t k = 0; k < factor_->nsuper; ++k) {
      const int k1 = super[k], k2 = super[k + 1];
      if (k2 <= first) continue;
      // A supernode's rows: its own columns k1..k2−1, then the rows below; its values column
      // by column with nsrow entries each (those above the diagonal are not part of L).
      const int nsrow = pi[k + 1] - pi[k];
      const int* rows = s + pi[k];
      const double* values = x + px[k];
      for (int j = std::max(k1, first); j < k2; ++j)
        for (int r = j - k1; r < nsrow; ++r)
          l_cc_(rows[r] - first, j - first) =
              values[static_cast<std::ptrdiff_t>(j - k1) * nsrow + r];
    }
  }

  /// b ← L⁻¹ b (CHOLMOD_L) or L⁻ᵀ b (CHOLMOD_Lt), in the permuted order: the streaming
  /// substitutions of supernodal_substitution.h on CHOLMOD's supernodes (no allocation).
  void substitute(int system, VectorXd& b) {
    const SupernodalLayout layout = solver_support::supernodal_layout(factor_);
    if (system == CHOLMOD_L)
      substitution_.forward(layout, b.data());
    else
      substitution_.back(layout, b.data());
  }

  int n_;
  cholmod_common common_{};
  cholmod_factor* factor_ = nullptr;
  MatrixXd l_cc_;  // trailing block of L (m × m, lower)
  VectorXd z_;     // L⁻¹ P r of the last condense
  VectorXd back_;  // the back substitution of recover (kept: no allocation per step)
  SubtreeSubstitution substitution_;  // planned for each factorization
};

/// Over any LinearSolver (the distributed MUMPS): G = A⁻¹ E by one solve with m right-hand
/// sides, S = (Eᵀ G)⁻¹ (symmetric positive definite when A is), x = A⁻¹ r − G S (y − x_c).
class TransferSchurSolver final : public SchurSolver {
 public:
  TransferSchurSolver(int n, std::vector<int> c)
      : SchurSolver(std::move(c)), solver_(make_linear_solver(n)) {}

  std::string name() const override { return solver_->name() + ", transfer matrix"; }

  void analyze_pattern(const SparseMatrix& lower) override {
    solver_->analyze_pattern(lower);
    counters_ = solver_->counters();
  }

  void factorize(const SparseMatrix& lower) override {
    solver_->factorize(lower);
    const auto n = static_cast<Eigen::Index>(lower.rows());
    const auto m = static_cast<Eigen::Index>(c_.size());
    MatrixXd e = MatrixXd::Zero(n, m);
    for (Eigen::Index k = 0; k < m; ++k) e(c_[static_cast<std::size_t>(k)], k) = 1.0;
    g_ = solver_->solve(e);
    MatrixXd h(m, m);
    for (Eigen::Index k = 0; k < m; ++k) h.row(k) = g_.row(c_[static_cast<std::size_t>(k)]);
    // Symmetrized (evaluated first: the transpose aliases the matrix assigned to).
    h = (0.5 * (h + h.transpose())).eval();
    const Eigen::LDLT<MatrixXd> ldlt(h);
    const MatrixXd inverse = ldlt.solve(MatrixXd::Identity(m, m));
    schur_ = 0.5 * (inverse + inverse.transpose());
    counters_ = solver_->counters();
  }

  VectorXd condense(const Eigen::Ref<const VectorXd>& r) override {
    x_ = solver_->solve(VectorXd(r));
    y_.resize(static_cast<Eigen::Index>(c_.size()));
    for (std::size_t k = 0; k < c_.size(); ++k) y_(static_cast<Eigen::Index>(k)) = x_(c_[k]);
    counters_ = solver_->counters();
    return y_;
  }

  void recover(const VectorXd& x_c, VectorXd& x) override {
    x = x_ - g_ * (schur_ * (y_ - x_c));
    for (std::size_t k = 0; k < c_.size(); ++k) x(c_[k]) = x_c(static_cast<Eigen::Index>(k));
  }

 private:
  std::unique_ptr<LinearSolver> solver_;
  MatrixXd g_;      // A⁻¹ E (n × m)
  VectorXd x_, y_;  // A⁻¹ r of the last condense, and its c part
};

}  // namespace

std::unique_ptr<SchurSolver> make_schur_solver(int n, std::vector<int> c, SchurSolverKind kind) {
  IMPACTFE_CHECK(!c.empty() && static_cast<int>(c.size()) < n,
                 fmt::format("SchurSolver: {} condensed rows of {}", c.size(), n));
  for (std::size_t k = 0; k < c.size(); ++k)
    IMPACTFE_CHECK(c[k] >= 0 && c[k] < n && (k == 0 || c[k - 1] < c[k]),
                   "SchurSolver: condensed rows must be ascending and distinct");
  if (kind == SchurSolverKind::Auto)
    kind = sparse_solver_replaced() ? SchurSolverKind::Transfer : SchurSolverKind::Factorization;
  if (kind == SchurSolverKind::Transfer)
    return std::make_unique<TransferSchurSolver>(n, std::move(c));
  return std::make_unique<CholmodSchurSolver>(n, std::move(c));
}

}  // namespace impactfe
