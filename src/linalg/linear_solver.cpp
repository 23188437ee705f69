#include "linalg/linear_solver.h"

#include <cholmod.h>
#include <fmt/format.h>

#include <Eigen/Dense>
#include <Eigen/SparseCholesky>
#include <algorithm>
#include <cmath>
#include <new>

#include "core/errors.h"
#include "core/memory_budget.h"
#include "linalg/solver_support.h"
#include "linalg/supernodal_factor.h"
#include "linalg/supernodal_substitution.h"

namespace impactfe {

namespace {

using solver_support::cholmod_lower_view;
using solver_support::kSingularPivot;
using solver_support::ScopedTimer;

/// Factorizations up to this many flops (CHOLMOD's count from the symbolic analysis) take
/// SupernodalFactor's inline kernels: below it CHOLMOD's bookkeeping and BLAS call overheads
/// dominate (issue 11, docs/benchmarks.md).
constexpr double kInlineFactorFlops = 5.0e7;
/// Bytes of a factor per structural nonzero: 8 for the value, with the supernodal row indices
/// and padding about 9.8 (measured: 705 MB for nnz(L) = 72.3 million on a brick mesh).
constexpr double kFactorBytesPerEntry = 9.5;

/// CHOLMOD supernodal LLᵀ (SupernodalFactor's kernels for small factors), falling back to
/// simplicial LDLᵀ for indefinite (but regular) effective matrices (e.g. compressive stress
/// stiffening).
class CholmodSolver final : public LinearSolver {
 public:
  CholmodSolver() {
    cholmod_start(&common_);
    common_.print = 0;
    common_.error_handler = nullptr;
    common_.supernodal = CHOLMOD_AUTO;
    common_.final_ll = 1;
    common_.quick_return_if_not_posdef = 1;
  }
  ~CholmodSolver() override {
    if (factor_) cholmod_free_factor(&factor_, &common_);
    cholmod_finish(&common_);
  }

  std::string name() const override { return "CHOLMOD"; }

  void analyze_pattern(const SparseMatrix& lower) override {
    ScopedTimer timer(counters_.analyze_seconds);
    if (factor_) cholmod_free_factor(&factor_, &common_);
    cholmod_sparse A = cholmod_lower_view(lower);
    factor_ = cholmod_analyze(&A, &common_);
    if (!factor_) {
      if (common_.status == CHOLMOD_OUT_OF_MEMORY) throw std::bad_alloc();
      throw std::runtime_error(fmt::format(
          "the sparse solver's symbolic analysis failed (CHOLMOD status {})", common_.status));
    }
    solver_support::require_blas_for(factor_);
    // The exact size of the factor is known now, before it is allocated: a model whose factor
    // cannot fit is refused here rather than run out of memory while factorizing.
    const double lnz = common_.lnz;
    const double n = static_cast<double>(lower.rows());
    try {
      require_memory(
          kFactorBytesPerEntry * lnz,
          fmt::format("the factor of the {:.0f} equations (nnz(L) = {:.4g} by the symbolic "
                      "analysis)",
                      n, lnz),
          fmt::format("at this fill, about {:.3g} equations would fit",
                      n * std::pow(memory_available().bytes / (kFactorBytesPerEntry * lnz), 0.75)));
    } catch (...) {
      cholmod_free_factor(&factor_, &common_);
      throw;
    }
    ++counters_.analyses;
    n_ = static_cast<int>(lower.rows());
    inline_.reset();
    if (common_.fl <= kInlineFactorFlops) {
      // Its own (supernodal) analysis must not change the figures of the one above.
      const double fl = common_.fl, lnz = common_.lnz;
      auto factor = std::make_unique<SupernodalFactor>();
      if (factor->analyze(lower, common_)) inline_ = std::move(factor);
      common_.fl = fl;
      common_.lnz = lnz;
    }
  }

  void factorize(const SparseMatrix& lower) override {
    if (!factor_) analyze_pattern(lower);
    ScopedTimer timer(counters_.factorize_seconds);
    if (inline_ && inline_->factorize(lower)) {
      ++counters_.factorizations;
      negative_pivots_ = 0;
      first_negative_row_ = -1;
      if (inline_->rcond() < 1e-13) check_pivots(lower);
      counters_.matrix_nonzeros = static_cast<long>(lower.nonZeros());
      counters_.factor_nonzeros = static_cast<long>(common_.lnz);
      counters_.factor_bytes = inline_->stored_bytes();
      return;
    }
    // Not positive definite (or a factor too large for the inline kernels): CHOLMOD's LLᵀ,
    // then its LDLᵀ, which tells an indefinite matrix from a singular one.
    // common_.fl: flop count of the factorization, from the symbolic analysis.
    cholmod_sparse A = cholmod_lower_view(lower);
    common_.final_ll = 1;
    cholmod_factorize(&A, factor_, &common_);
    ++counters_.factorizations;
    negative_pivots_ = 0;
    first_negative_row_ = -1;
    if (common_.status == CHOLMOD_OUT_OF_MEMORY) throw std::bad_alloc();
    if (common_.status == CHOLMOD_NOT_POSDEF || factor_->minor < factor_->n) {
      // Retry as LDLᵀ: regular but indefinite matrices factor; a zero pivot stays singular.
      cholmod_free_factor(&factor_, &common_);
      const int saved = common_.supernodal;
      common_.supernodal = CHOLMOD_SIMPLICIAL;
      common_.final_ll = 0;
      factor_ = cholmod_analyze(&A, &common_);
      cholmod_factorize(&A, factor_, &common_);
      common_.supernodal = saved;
      if (common_.status != CHOLMOD_OK || factor_->minor < factor_->n) {
        const int column = factor_->minor < factor_->n
                               ? static_cast<const int*>(factor_->Perm)[factor_->minor]
                               : weakest_pivot_row(lower);
        cholmod_free_factor(&factor_, &common_);
        throw SingularMatrixError(column, "zero pivot in the factorization");
      }
      check_pivots(lower);
      count_negative_pivots();
      record_sizes(lower);
      return;
    }
    // rcond is (min L_jj / max L_jj)^2: only a near-mechanism gets below 1e-13; then diagnose.
    if (cholmod_rcond(factor_, &common_) < 1e-13) check_pivots(lower);
    record_sizes(lower);
    if (factor_->is_super) substitution_.plan(solver_support::supernodal_layout(factor_));
  }

  VectorXd solve(const VectorXd& b) override {
    if (inline_ && inline_->valid()) {
      ScopedTimer timer(counters_.solve_seconds);
      ++counters_.solves;
      return inline_->solve(b);
    }
    IMPACTFE_CHECK(factor_ != nullptr, "CHOLMOD: solve before factorize");
    if (!factor_->is_super) {
      MatrixXd B = b;
      return solve(B).col(0);
    }
    // One right-hand side with a supernodal LLᵀ factor: the streaming substitutions of
    // supernodal_substitution.h (a transient's step; 40 % of CHOLMOD's solve time on a shell
    // factor, docs/benchmarks.md).
    ScopedTimer timer(counters_.solve_seconds);
    const auto* perm = static_cast<const int*>(factor_->Perm);
    const auto n = static_cast<Eigen::Index>(b.size());
    permuted_.resize(n);
    for (Eigen::Index k = 0; k < n; ++k) permuted_(k) = b(perm[k]);
    const SupernodalLayout layout = solver_support::supernodal_layout(factor_);
    substitution_.forward(layout, permuted_.data());
    substitution_.back(layout, permuted_.data());
    VectorXd x(n);
    for (Eigen::Index k = 0; k < n; ++k) x(perm[k]) = permuted_(k);
    ++counters_.solves;
    return x;
  }

  MatrixXd solve(const MatrixXd& B) override {
    IMPACTFE_CHECK(factor_ != nullptr, "CHOLMOD: solve before factorize");
    ScopedTimer timer(counters_.solve_seconds);
    if (inline_ && inline_->valid()) {
      counters_.solves += B.cols();
      return inline_->solve(B);
    }
    cholmod_dense rhs;
    rhs.nrow = static_cast<size_t>(B.rows());
    rhs.ncol = static_cast<size_t>(B.cols());
    rhs.nzmax = rhs.nrow * rhs.ncol;
    rhs.d = rhs.nrow;
    rhs.x = const_cast<double*>(B.data());
    rhs.z = nullptr;
    rhs.xtype = CHOLMOD_REAL;
    rhs.dtype = CHOLMOD_DOUBLE;
    cholmod_dense* x = cholmod_solve(CHOLMOD_A, factor_, &rhs, &common_);
    if (!x) {
      if (common_.status == CHOLMOD_OUT_OF_MEMORY) throw std::bad_alloc();
      throw std::runtime_error(
          fmt::format("the sparse solver's solve failed (CHOLMOD status {})", common_.status));
    }
    MatrixXd X = Eigen::Map<MatrixXd>(static_cast<double*>(x->x), B.rows(), B.cols());
    cholmod_free_dense(&x, &common_);
    counters_.solves += B.cols();
    return X;
  }

 private:
  /// Counts the negative entries of D in a simplicial LDLᵀ factor (the diagonal is the first
  /// entry of each column) and maps the first to its unpermuted row.
  void count_negative_pivots() {
    if (factor_->is_super || factor_->is_ll) return;
    const auto* p = static_cast<const int*>(factor_->p);
    const auto* x = static_cast<const double*>(factor_->x);
    const auto* perm = static_cast<const int*>(factor_->Perm);
    for (std::size_t j = 0; j < factor_->n; ++j)
      if (x[p[j]] < 0.0) {
        if (negative_pivots_++ == 0) first_negative_row_ = perm ? perm[j] : static_cast<int>(j);
      }
  }

  /// Sizes of the factor just computed. common_.lnz is nnz(L) of the last symbolic analysis
  /// (set by cholmod_analyze; the LDLᵀ retry re-analyzes). The bytes are what a solve reads:
  /// the dense supernode blocks and their row indices, or the simplicial columns.
  void record_sizes(const SparseMatrix& lower) {
    counters_.matrix_nonzeros = static_cast<long>(lower.nonZeros());
    counters_.factor_nonzeros = static_cast<long>(common_.lnz);
    if (factor_->is_super) {
      counters_.factor_bytes =
          static_cast<long>(factor_->xsize * sizeof(double) + factor_->ssize * sizeof(int));
    } else {
      const int* column_nz = static_cast<const int*>(factor_->nz);
      long stored = 0;
      for (size_t j = 0; j < factor_->n; ++j) stored += column_nz[j];
      counters_.factor_bytes = stored * static_cast<long>(sizeof(double) + sizeof(int));
    }
  }

  /// A tiny pivot relative to its diagonal means a mechanism: name the weakest equation.
  void check_pivots(const SparseMatrix& lower) {
    const int row = weakest_pivot_row(lower);
    if (row >= 0) throw SingularMatrixError(row, "near-zero pivot in the factorization");
  }

  cholmod_common common_{};
  cholmod_factor* factor_ = nullptr;
  std::unique_ptr<SupernodalFactor> inline_;  // small factors: the inline kernels
  VectorXd permuted_;                         // a solve's right-hand side in the factor's order
  SubtreeSubstitution substitution_;          // planned for each supernodal factor
  int n_ = 0;
};

/// Dense LDLᵀ with pivoting, for small systems (reduced master sets, tiny models).
class DenseSolver final : public LinearSolver {
 public:
  std::string name() const override { return "dense LDLT"; }
  void analyze_pattern(const SparseMatrix&) override { ++counters_.analyses; }
  void factorize(const SparseMatrix& lower) override {
    ScopedTimer timer(counters_.factorize_seconds);
    MatrixXd A = MatrixXd::Zero(lower.rows(), lower.cols());
    for (Eigen::Index j = 0; j < lower.outerSize(); ++j)
      for (SparseMatrix::InnerIterator it(lower, j); it; ++it) A(it.row(), it.col()) = it.value();
    ++counters_.factorizations;
    // A dense factor: the solves read its lower triangle.
    const long n = static_cast<long>(A.rows());
    counters_.matrix_nonzeros = static_cast<long>(lower.nonZeros());
    counters_.factor_nonzeros = n * (n + 1) / 2;
    counters_.factor_bytes = counters_.factor_nonzeros * static_cast<long>(sizeof(double));
    negative_pivots_ = 0;
    first_negative_row_ = -1;
    double scale = 0.0;
    for (int i = 0; i < A.rows(); ++i) scale = std::max(scale, std::abs(A(i, i)));
    if (A.rows() == 0) return;
    // Positive definite with no pivot near the singular threshold (the usual effective matrix):
    // Cholesky without pivoting (the thesis superelement use pass factors its 27 x 27 tangent
    // 202 times: 10.0 M -> 6.4 M instructions). Otherwise the pivoted LDLᵀ, which names the
    // equation of a zero pivot and counts the negative ones.
    llt_.compute(A);  // reads the lower triangle
    use_llt_ = llt_.info() == Eigen::Success;
    if (use_llt_) {
      const auto diagonal = llt_.matrixLLT().diagonal();
      for (int i = 0; i < diagonal.size() && use_llt_; ++i)
        use_llt_ = diagonal(i) * diagonal(i) > 1e3 * kSingularPivot * scale;
    }
    if (use_llt_) return;
    A = A.selfadjointView<Eigen::Lower>();
    ldlt_.compute(A);
    const VectorXd d = ldlt_.vectorD();
    for (int i = 0; i < d.size(); ++i) {
      if (!(std::abs(d(i)) > kSingularPivot * std::max(scale, 1e-300))) {
        // Map the permuted pivot back to the equation it belongs to.
        Eigen::VectorXi perm = Eigen::VectorXi::LinSpaced(A.rows(), 0, A.rows() - 1);
        perm = ldlt_.transpositionsP() * perm;
        throw SingularMatrixError(perm(i), "zero pivot in the factorization");
      }
    }
    for (int i = 0; i < d.size(); ++i)
      if (d(i) < 0.0 && negative_pivots_++ == 0) {
        Eigen::VectorXi perm = Eigen::VectorXi::LinSpaced(A.rows(), 0, A.rows() - 1);
        perm = ldlt_.transpositionsP() * perm;
        first_negative_row_ = perm(i);
      }
  }
  VectorXd solve(const VectorXd& b) override {
    ScopedTimer timer(counters_.solve_seconds);
    ++counters_.solves;
    return use_llt_ ? VectorXd(llt_.solve(b)) : VectorXd(ldlt_.solve(b));
  }
  MatrixXd solve(const MatrixXd& B) override {
    ScopedTimer timer(counters_.solve_seconds);
    counters_.solves += B.cols();
    return use_llt_ ? MatrixXd(llt_.solve(B)) : MatrixXd(ldlt_.solve(B));
  }

 private:
  Eigen::LLT<MatrixXd> llt_;
  Eigen::LDLT<MatrixXd> ldlt_;
  bool use_llt_ = false;
};

}  // namespace

SolverCounters& SolverCounters::operator+=(const SolverCounters& other) {
  analyses += other.analyses;
  factorizations += other.factorizations;
  solves += other.solves;
  analyze_seconds += other.analyze_seconds;
  factorize_seconds += other.factorize_seconds;
  solve_seconds += other.solve_seconds;
  matrix_nonzeros = std::max(matrix_nonzeros, other.matrix_nonzeros);
  factor_nonzeros = std::max(factor_nonzeros, other.factor_nonzeros);
  factor_bytes = std::max(factor_bytes, other.factor_bytes);
  return *this;
}

int weakest_pivot_row(const SparseMatrix& lower) {
  Eigen::SimplicialLDLT<SparseMatrix, Eigen::Lower> ldlt(lower);
  const VectorXd d = ldlt.vectorD();
  const auto& perm = ldlt.permutationP();
  // Pivot j of the permuted matrix belongs to original row perm^-1(j).
  const Eigen::PermutationMatrix<Eigen::Dynamic, Eigen::Dynamic, int> inverse_perm = perm.inverse();
  const Eigen::VectorXi& inverse = inverse_perm.indices();
  int worst = -1;
  double worst_ratio = kSingularPivot;  // only pivots below this count
  for (int j = 0; j < d.size(); ++j) {
    const int row = inverse(j);
    const double diag = std::abs(lower.coeff(row, row));
    // |pivot| relative to its diagonal: a negative pivot of an indefinite but regular matrix
    // (compressive stress stiffening) is fine; a vanishing one is a mechanism.
    const double ratio = diag > 0.0 ? std::abs(d(j)) / diag : (d(j) != 0.0 ? 1.0 : 0.0);
    if (ratio < worst_ratio) {
      worst_ratio = ratio;
      worst = row;
    }
  }
  return worst;
}

namespace {
SparseSolverFactory sparse_solver_factory = nullptr;
}  // namespace

bool sparse_solver_replaced() {
  return sparse_solver_factory != nullptr;
}

void set_sparse_solver_factory(SparseSolverFactory factory) {
  sparse_solver_factory = factory;
}

std::unique_ptr<LinearSolver> make_linear_solver(int n, LinearSolverKind kind) {
  if (kind == LinearSolverKind::Dense || (kind == LinearSolverKind::Auto && n <= 64))
    return std::make_unique<DenseSolver>();
  if (kind == LinearSolverKind::Auto && sparse_solver_factory) return sparse_solver_factory();
  return std::make_unique<CholmodSolver>();
}

}  // namespace impactfe
