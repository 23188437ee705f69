#pragma once
/// Sparse assembly with the pattern built once. Forms the effective matrix
/// K_eff = cK K_T + cC C + cM M on the free DOFs (lower triangle, for the linear solver) and the
/// element force vectors on all active DOFs, in one pass over the elements
/// (the OpenSees/Chrono contract: the integrator supplies the coefficients).
#include <memory>
#include <string>
#include <vector>

#include "assembly/dof_graph.h"
#include "assembly/dof_map.h"
#include "elements/element.h"
#include "linalg/shared_pattern_products.h"
#include "linalg/sparse.h"
#include "time/time_integrator.h"

namespace impactfe {

class Assembler {
 public:
  /// `alpha`, `beta`: Rayleigh damping C += alpha M + beta K (ALPHAD, BETAD), element by element
  /// with the current tangent.
  Assembler(const std::vector<std::unique_ptr<Element>>& elements, const DofMap& dofs,
            const ElementContext& ctx, double alpha = 0.0, double beta = 0.0);

  /// Stiffness-proportional damping of each element's material (MP,DAMP = BETD: C_e += β_e K_e,
  /// APDL_MODELING §6.1), added to the global beta; one value per element, in element order.
  void set_material_stiffness_damping(std::vector<double> beta);

  const DofMap& dofs() const { return dofs_; }
  const ElementContext& context() const { return ctx_; }

  /// Distributed assembly (MUMPS on several ranks, docs/scaling.md "Element assembly split by
  /// rank"): `column_owner` is the rank that hands each free column of the effective matrix to
  /// the solver (LinearSolver::column_owners; empty: not distributed, the default). Every
  /// active DOF then has an owner rank (a free one its column's; a constrained one the owner of
  /// the lowest-numbered element at it that has a free DOF), every element too (the owner of its
  /// lowest free DOF), and this rank's assemble() evaluates only the elements at DOFs it owns
  /// (owned elements plus a one-element layer of neighbours): the effective matrix is right
  /// only in this rank's columns (the only ones its solver reads), and each force vector entry
  /// is computed by its owner, in element order as one process sums it, and copied to every
  /// rank, so the vectors are the one-process vectors bit for bit whatever the rank count.
  /// Elements' status and history are untouched (their updates stay on every rank). Collective
  /// from then on: every rank calls assemble() in lockstep (SPMD).
  void distribute(const std::vector<int>& column_owner);
  /// One line for the run summary: elements owned and evaluated and the seconds spent in
  /// element assembly on each rank (collective when distributed).
  std::string assembly_summary() const;

  /// What one pass computes. Pointers left null are skipped.
  struct Output {
    SparseMatrix* effective = nullptr;   // free-free lower triangle of cK K + cC C + cM M
    VectorXd* internal_force = nullptr;  // f_int(u) over all active DOFs
    VectorXd* damping_force = nullptr;   // C v over all active DOFs
    VectorXd* inertia_force = nullptr;   // M a over all active DOFs (needs `a`)
    /// A factorization at the same u follows (the first Newton iteration of a step): the
    /// reusable nonlinear elements form their tangents with these forces, in one evaluation,
    /// and the factorization finds them in the buffers.
    bool tangent_follows = false;
  };
  /// u, v, a: total displacement, velocity and acceleration over all active DOFs (a only for
  /// the inertia force).
  void assemble(const IntegrationCoefficients& coeff, const VectorXd& u, const VectorXd& v,
                const Output& out, const VectorXd* a = nullptr) const;

  // ---- the split into a linear part and the nonlinear elements (condensed transient) ---------
  /// Free DOF indices touched by the nonlinear elements, ascending.
  std::vector<int> nonlinear_free_dofs() const;
  /// Effective matrix of the linear part, cK K_L + cC C_L + cM M: the stiffness and damping of
  /// the linear elements and the mass of every element (free-free lower triangle).
  void assemble_linear_part(const IntegrationCoefficients& coeff, SparseMatrix& effective) const;
  /// The nonlinear elements' share of the residual and of the effective tangent, on the DOFs
  /// numbered by `position` (active index → position, −1 for DOFs left out):
  /// phi += w (f_int + C v),  tangent += cK K_T + cC C  (C with the Rayleigh terms).
  void assemble_nonlinear_part(const IntegrationCoefficients& coeff, double w, const VectorXd& u,
                               const VectorXd& v, const std::vector<int>& position, VectorXd& phi,
                               MatrixXd* tangent) const;
  int n_nonlinear_elements() const { return static_cast<int>(nonlinear_.size()); }
  /// Runs the nonlinear elements' tangent phase on every allowed thread from the first pass,
  /// without the timing probes of TangentThreading (for tests of the parallel loop: the results
  /// are the same either way).
  void force_parallel_tangents() const {
    threading_.probes_left = 0;
    threading_.parallel = true;
  }

  /// M a over all active DOFs (the same product as Output::inertia_force).
  VectorXd inertia_force(const VectorXd& a) const;
  /// The same into `f` (resized; its storage reused).
  void inertia_force(const VectorXd& a, VectorXd& f) const;
  /// The mass matrix's diagonal over all active DOFs (from the global products).
  VectorXd mass_diagonal() const;
  /// Lower triangle (column-compressed) of the mass matrix on the DOFs i with position[i] >= 0
  /// (indices past the end of `position` count as -1), numbered by position (`size` of them),
  /// from the global products. Exact zeros are left out: the products keep M on the union
  /// pattern of K, C and M, and a consistent shell mass, which couples only like components,
  /// then factors to a sixth of K's factor instead of all of it.
  SparseMatrix mass_block_lower(const std::vector<int>& position, int size) const;
  /// Mass matrix over all active DOFs (full symmetric storage), for inertia forces M a and the
  /// frame-acceleration load -M r a.
  SparseMatrix mass_matrix() const;
  /// Stiffness at u (full symmetric storage, all active DOFs): for energies and reduction.
  SparseMatrix stiffness_matrix(const VectorXd& u) const;
  /// Damping matrix at u (full symmetric storage, all active DOFs).
  SparseMatrix damping_matrix(const VectorXd& u) const;
  bool has_damping() const { return has_damping_; }
  /// True when some element's stiffness or internal force depends on u (or on a status).
  bool is_nonlinear() const;
  /// The free-free lower pattern of every effective matrix (formed again from the DOF graph
  /// when assemble_linear_part released it).
  const SparsePattern& pattern() const;

  /// Element DOF values gathered from a global vector.
  void gather(std::size_t e, const VectorXd& global, VectorXd& local) const;

 private:
  enum class Which { Stiffness, Mass, Damping };
  SparseMatrix full_matrix(Which which, const VectorXd& u) const;
  /// Element damping matrix at ue (element dampers + Rayleigh α M_e + β K_e, with K_e = k and
  /// M_e = m); false when none.
  bool element_damping(std::size_t e, const VectorXd& ue, const MatrixXd& k, const MatrixXd& m,
                       MatrixXd& c) const;
  /// A linear element's stiffness (at u = 0), and its mass, evaluated (they are not stored).
  void linear_element_stiffness(std::size_t e, MatrixXd& k) const;
  void linear_element_matrices(std::size_t e, MatrixXd& k, MatrixXd& m) const;
  /// values += the lower triangle of a_factor·a (+ b_factor·b when b is given), element e.
  void scatter_lower(std::size_t e, double a_factor, const MatrixXd& a, double b_factor,
                     const MatrixXd* b, double* values) const;
  /// The effective matrix's values that are constant for the coefficients: the linear
  /// elements' cK K + cC C and every element's cM M, formed once per coefficient set (a
  /// Newton iteration then adds only the nonlinear elements' tangents).
  const std::vector<double>& constant_effective(const IntegrationCoefficients& coeff) const;
  /// values += that constant part, from the global products, on a matrix with the pattern's
  /// structure (`column_start`, `row`: its compressed-column index arrays).
  void add_constant_effective(const IntegrationCoefficients& coeff, const int* column_start,
                              const int* row, double* values) const;
  mutable std::vector<double> constant_effective_;
  mutable IntegrationCoefficients constant_coeff_{};
  /// Forms linear_products_ from the element matrices, summed on the DOF graph.
  void build_linear_force_matrices(const DofGraph& graph);
  /// Calls visit(row, column, values) once for each entry of the global products' lower
  /// triangle (row >= column; values: K, C, M there). With symmetric storage the entries come
  /// column by column, rows ascending within a column.
  template <class Visit>
  void for_each_lower_product_entry(Visit&& visit) const;
  /// The force outputs after the tangent phase: the linear part from the stored global
  /// products, the nonlinear elements element by element.
  void add_forces(const VectorXd& u, const VectorXd& v, const VectorXd* a, const Output& out,
                  const std::vector<char>* only) const;

  // ---- distributed assembly (distribute) ----
  std::vector<int> dof_owner_;          // owner rank of each active DOF (empty: one process)
  std::vector<int> element_owner_;      // owner rank of each element
  std::vector<char> evaluate_matrix_;   // element at a free column this rank owns
  std::vector<char> evaluate_vectors_;  // element at an active DOF this rank owns
  int rank_ = 0;
  int ranks_ = 1;
  mutable double element_seconds_ = 0.0;      // time in assemble() (the vector exchange excluded)
  mutable double element_cpu_seconds_ = 0.0;  // the same in process CPU time

  const std::vector<std::unique_ptr<Element>>& elements_;
  const DofMap& dofs_;
  ElementContext ctx_;
  // The DOF graph (DofGraph) is not kept: it is built again for the few whole-model matrices
  // (full_matrix) and material damping, once per analysis (issue 11: memory).
  // The pattern is released by assemble_linear_part: the condensed transient's effective matrix
  // then holds the only copy of it while CHOLMOD factors (the peak memory of a large run), and
  // a later full assembly forms it again (pattern()).
  mutable SparsePattern pattern_;
  long long pattern_nonzeros_ = 0;
  /// For each nonlinear element (empty for the linear ones), its lower-triangle entries (a, b),
  /// a >= b, whose DOFs are both free: the entry's index in the column-major element matrix
  /// and its value slot in the lower pattern. The scatter is then an indexed add without a
  /// test per entry (the constrained DOFs' entries are not in the list).
  struct ScatterEntry {
    int element_entry;  // b n + a
    int slot;
  };
  std::vector<std::vector<ScatterEntry>> scatter_;
  /// Constant mass matrices of the nonlinear elements (empty for the linear ones, whose K_e,
  /// C_e and M_e are only in linear_products_).
  std::vector<MatrixXd> mass_;
  std::vector<bool> is_linear_;
  std::vector<std::size_t> nonlinear_;  // indices of the nonlinear elements
  /// Σ K_e and Σ C_e of the linear elements and Σ M_e of all over the active DOFs, on one
  /// pattern: the linear part of f_int, C v and M a in one pass per residual instead of an
  /// element loop (issue 11: a step costs a solve plus O(nnz) vector work).
  SharedPatternProducts linear_products_;
  // Per-element results of the tangent phase (scratch, not state).
  mutable std::vector<MatrixXd> tangent_buffer_;
  mutable std::vector<VectorXd> force_buffer_;
  /// Reuse of the buffers: a Newton iteration evaluates the residual and then factors the
  /// tangent at the same iterate, i.e. two element phases at one u. An element without status
  /// and without history (the co-rotational shell, the large-deflection brick) is a pure
  /// function of its DOF values (ctx_ is fixed for the assembler's life), so when its gathered
  /// values are bitwise those of its last evaluation the buffers are already its answer: the
  /// results are bitwise the same. Elements with a status (gaps, contact) or history
  /// (plasticity) are always evaluated. `buffers_at_[e]` is 0 while the buffers hold nothing
  /// reusable; `gathered_[e]` is the element's scratch for its gathered values.
  ///
  /// The tangent is formed only when asked for: a residual evaluates the internal forces
  /// alone (Element::internal_force), and the factorization that follows at the same iterate
  /// adds the tangent. The evaluation that finds an iterate converged (one per step) thus
  /// never forms a tangent; the helmet's shells spent 44 % of their tangents there. The
  /// residual of a step's predictor, which a factorization almost always follows, forms both at
  /// once (Output::tangent_follows): one evaluation instead of two.
  /// `tangent_valid_[e]`: the tangent buffer belongs to tangent_at_[e] too.
  std::vector<bool> reusable_;
  mutable std::vector<VectorXd> tangent_at_;
  mutable std::vector<VectorXd> gathered_;
  mutable std::vector<char> buffers_at_;
  mutable std::vector<char> tangent_valid_;
  /// Internal forces (and tangents when `with_tangent`) of the nonlinear elements at u into the
  /// buffers (only those with (*only)[e] set when `only` is given: distributed assembly).
  /// `tangent_follows`: the reusable elements that a factorization would evaluate form their
  /// tangents too (Output::tangent_follows).
  void compute_nonlinear_tangents(const VectorXd& u, bool with_tangent,
                                  const std::vector<char>* only = nullptr,
                                  bool tangent_follows = false) const;
  /// One element's phase; false when the buffers were reused (no evaluation).
  bool evaluate_tangent(std::size_t e, const VectorXd& u, bool with_tangent) const;

  /// Whether the tangent phase runs on several threads (core/thread_pool.h), decided from its
  /// measured cost: a parallel loop costs a wake-up of the workers, which on small per-step
  /// work or a busy machine costs more than it saves (issue 11). So the first
  /// kProbes passes run serially and are timed; the phase goes parallel only when the fastest of
  /// them took at least kMinParallelSeconds and more than one thread is allowed. The results are
  /// the same either way (per-element buffers, serial scatter).
  struct TangentThreading {
    static constexpr int kProbes = 3;
    static constexpr double kMinParallelSeconds = 2.0e-3;
    int probes_left = kProbes;
    double fastest_serial_seconds = 1e300;
    bool parallel = false;
    /// The last pass formed tangents ahead of a factorization, which then evaluates only the
    /// elements with a status or history: no probe of a full pass.
    bool formed_ahead = false;
    void record_serial_pass(double seconds);
  };
  mutable TangentThreading threading_;
  bool has_damping_ = false;
  double alpha_ = 0.0;                 // Rayleigh mass coefficient
  double beta_ = 0.0;                  // Rayleigh stiffness coefficient
  std::vector<double> material_beta_;  // per element (empty: none)
  double beta_of(std::size_t e) const {
    return material_beta_.empty() ? beta_ : beta_ + material_beta_[e];
  }
  /// The element's own damping (its dampers, its material's ALPD / BETD) is not zero.
  bool own_damping(std::size_t e) const;
  /// The element's own damping matrix at ue: its dampers' plus α M_e + β K_e of its material
  /// (Element::material_damping; k = K_e at ue, m = M_e), summed in the order of the element
  /// adapter this replaced (same values bitwise).
  void own_damping_matrix(std::size_t e, const VectorXd& ue, const MatrixXd& k, const MatrixXd& m,
                          MatrixXd& c) const;
  /// The tangent at u enters the element's damping forces (a β of BETAD, DAMP or BETD).
  bool damping_reads_tangent(std::size_t e) const {
    return beta_of(e) != 0.0 || elements_[e]->material_damping().beta != 0.0;
  }
};

}  // namespace impactfe
