#include "assembly/assembler.h"

#include <algorithm>
#include <chrono>
#include <cstring>
#include <ctime>
#include <exception>

#include <fmt/format.h>

#include "core/errors.h"
#include "core/thread_pool.h"
#include "linalg/parallel_backend.h"

namespace impactfe {

Assembler::Assembler(const std::vector<std::unique_ptr<Element>>& elements, const DofMap& dofs,
                     const ElementContext& ctx, double alpha, double beta)
    : elements_(elements), dofs_(dofs), ctx_(ctx), alpha_(alpha), beta_(beta) {
  const int nf = dofs_.n_free();
  const DofGraph graph(dofs_, elements_.size());
  // Pattern: every pair of free DOFs that share an element (lower triangle), every diagonal.
  pattern_ = graph.lower_pattern(nf);
  pattern_nonzeros_ = pattern_.nonzeros();

  scatter_.resize(elements_.size());
  mass_.resize(elements_.size());
  is_linear_.assign(elements_.size(), false);
  tangent_buffer_.resize(elements_.size());
  force_buffer_.resize(elements_.size());
  tangent_at_.resize(elements_.size());
  gathered_.resize(elements_.size());
  buffers_at_.assign(elements_.size(), 0);
  tangent_valid_.assign(elements_.size(), 0);
  reusable_.assign(elements_.size(), false);
  for (std::size_t e = 0; e < elements_.size(); ++e) {
    has_damping_ = has_damping_ || own_damping(e) || alpha_ != 0.0 || beta_ != 0.0;
    // Linear elements: K_e, C_e and M_e go into the global products once
    // (build_linear_force_matrices) and from there into every effective matrix. The nonlinear
    // elements keep M_e (their Rayleigh α M_e) and the slots their tangents are scattered to.
    if (!elements_[e]->is_nonlinear(ctx_)) {
      is_linear_[e] = true;
      continue;
    }
    nonlinear_.push_back(e);
    reusable_[e] = !elements_[e]->has_status() && !elements_[e]->has_history();
    elements_[e]->mass(ctx_, mass_[e]);
    const auto& idx = dofs_.element_indices(e);
    const int n = static_cast<int>(idx.size());
    auto& scatter = scatter_[e];
    scatter.clear();
    // Column b of the element matrix, rows a >= b (contiguous in memory), in that order.
    for (int b = 0; b < n; ++b)
      for (int a = b; a < n; ++a) {
        int row = idx[a], col = idx[b];
        if (row >= nf || col >= nf) continue;
        if (row < col) std::swap(row, col);
        // Binary search of `row` within column `col`.
        const int* rows = pattern_.row.data();
        const int* begin = rows + pattern_.column_start[static_cast<std::size_t>(col)];
        const int* end = rows + pattern_.column_start[static_cast<std::size_t>(col) + 1];
        const int* it = std::lower_bound(begin, end, row);
        scatter.push_back({b * n + a, static_cast<int>(it - rows)});
        // Two DOFs of the element coupled into one (CP) land on one diagonal entry, which
        // takes both K_ab and K_ba: the upper triangle's entry is not scattered otherwise.
        if (a != b && row == col) scatter.push_back({a * n + b, static_cast<int>(it - rows)});
      }
    scatter.shrink_to_fit();
  }
  build_linear_force_matrices(graph);
}

void Assembler::linear_element_stiffness(std::size_t e, MatrixXd& k) const {
  const VectorXd zero = VectorXd::Zero(elements_[e]->n_dofs());
  VectorXd f;
  elements_[e]->tangent(ctx_, zero, k, f);
}

void Assembler::linear_element_matrices(std::size_t e, MatrixXd& k, MatrixXd& m) const {
  linear_element_stiffness(e, k);
  elements_[e]->mass(ctx_, m);
}

void Assembler::build_linear_force_matrices(const DofGraph& graph) {
  // The linear elements' stiffness and damping are constant (the condensed transient's A_L
  // relies on it too): evaluated at u = 0, summed on the DOF graph in element order (the order
  // of the triplet assembly this replaced: same values bitwise) and not kept element by element
  // (issue 11: the products are the model's only copy of them; 236 MB of element matrices on
  // the 155 522-DOF shell dome).
  GraphMatrix stiffness(graph), damping(graph), mass(graph);
  MatrixXd k, m, c;
  std::vector<int> slots;
  for (std::size_t e = 0; e < elements_.size(); ++e) {
    graph.element_slots(dofs_.element_indices(e), slots);
    if (!is_linear_[e]) {
      mass.add(slots, mass_[e], false);
      continue;
    }
    linear_element_matrices(e, k, m);
    mass.add(slots, m, false);
    stiffness.add(slots, k, false);
    if (element_damping(e, VectorXd::Zero(k.rows()), k, m, c)) damping.add(slots, c, false);
  }
  // An entry is kept where any of the three received a contribution (a matrix nothing was added
  // to has no flags).
  std::vector<unsigned char> kept(static_cast<std::size_t>(graph.n_entries()), 0);
  for (GraphMatrix* m : {&stiffness, &damping, &mass}) {
    for (std::size_t s = 0; s < m->touched.size(); ++s) kept[s] |= m->touched[s];
    std::vector<unsigned char>().swap(m->touched);
  }
  linear_products_ = SharedPatternProducts(
      graph.row_start(), graph.column(), kept,
      {std::move(stiffness.value), std::move(damping.value), std::move(mass.value)});
}

void Assembler::set_material_stiffness_damping(std::vector<double> beta) {
  IMPACTFE_CHECK(beta.empty() || beta.size() == elements_.size(),
                 "material damping: one value per element expected");
  // All zero (no MP,DAMP): nothing changes, and the linear products need no second build.
  if (std::all_of(beta.begin(), beta.end(), [](double b) { return b == 0.0; }) &&
      material_beta_.empty())
    return;
  material_beta_ = std::move(beta);
  for (double b : material_beta_) has_damping_ = has_damping_ || b != 0.0;
  build_linear_force_matrices(DofGraph(dofs_, elements_.size()));
  constant_effective_.clear();  // the linear elements' damping changed
}

bool Assembler::own_damping(std::size_t e) const {
  const Element::MaterialDamping& d = elements_[e]->material_damping();
  return elements_[e]->has_damping() || d.alpha != 0.0 || d.beta != 0.0;
}

void Assembler::own_damping_matrix(std::size_t e, const VectorXd& ue, const MatrixXd& k,
                                   const MatrixXd& m, MatrixXd& c) const {
  const Element::MaterialDamping& d = elements_[e]->material_damping();
  elements_[e]->damping(ctx_, ue, c);
  if (d.alpha != 0.0) c += d.alpha * m;
  if (d.beta != 0.0) c += d.beta * k;
}

void Assembler::gather(std::size_t e, const VectorXd& global, VectorXd& local) const {
  const auto& idx = dofs_.element_indices(e);
  local.resize(static_cast<int>(idx.size()));
  for (std::size_t a = 0; a < idx.size(); ++a) local(static_cast<int>(a)) = global(idx[a]);
}

void Assembler::distribute(const std::vector<int>& column_owner) {
  dof_owner_.clear();
  element_owner_.clear();
  evaluate_matrix_.clear();
  evaluate_vectors_.clear();
  rank_ = process_rank();
  ranks_ = process_count();
  if (column_owner.empty() || ranks_ <= 1) return;
  const int nf = dofs_.n_free();
  IMPACTFE_CHECK(static_cast<int>(column_owner.size()) == nf,
                 "distributed assembly: one owner per free DOF expected");
  const std::size_t ne = elements_.size();
  // Deterministic from the solver's partition alone, so every rank derives the same maps.
  element_owner_.assign(ne, -1);
  dof_owner_.assign(static_cast<std::size_t>(dofs_.n_active()), -1);
  for (int i = 0; i < nf; ++i)
    dof_owner_[static_cast<std::size_t>(i)] = column_owner[static_cast<std::size_t>(i)];
  for (std::size_t e = 0; e < ne; ++e) {
    int lowest = nf;
    for (int i : dofs_.element_indices(e)) lowest = std::min(lowest, i);
    if (lowest < nf) element_owner_[e] = column_owner[static_cast<std::size_t>(lowest)];
  }
  // A constrained DOF goes with the lowest-numbered element at it that has a free DOF (its
  // reaction is summed where most of its elements are evaluated anyway), else to rank 0.
  for (std::size_t e = 0; e < ne; ++e)
    for (int i : dofs_.element_indices(e))
      if (element_owner_[e] >= 0 && dof_owner_[static_cast<std::size_t>(i)] < 0)
        dof_owner_[static_cast<std::size_t>(i)] = element_owner_[e];
  for (int& o : dof_owner_) o = std::max(o, 0);
  evaluate_matrix_.assign(ne, 0);
  evaluate_vectors_.assign(ne, 0);
  for (std::size_t e = 0; e < ne; ++e) {
    const auto& idx = dofs_.element_indices(e);
    if (element_owner_[e] < 0)
      element_owner_[e] =
          idx.empty()
              ? 0
              : dof_owner_[static_cast<std::size_t>(*std::min_element(idx.begin(), idx.end()))];
    for (int i : idx) {
      const bool mine = dof_owner_[static_cast<std::size_t>(i)] == rank_;
      evaluate_vectors_[e] = static_cast<char>(evaluate_vectors_[e] || mine);
      evaluate_matrix_[e] = static_cast<char>(evaluate_matrix_[e] || (mine && i < nf));
    }
  }
}

std::string Assembler::assembly_summary() const {
  // Wall clock and CPU time: on an oversubscribed machine the ranks' wall clocks include the
  // time they wait for a core, their CPU time is the work.
  const std::vector<double> seconds = values_of_all_ranks(element_seconds_);
  const std::vector<double> cpu = values_of_all_ranks(element_cpu_seconds_);
  if (dof_owner_.empty())
    return ranks_ > 1 ? fmt::format(
                            "element assembly on {} MPI ranks, not split: {} elements, "
                            "{:.4f} s ({:.4f} s CPU)",
                            ranks_, elements_.size(), seconds.front(), cpu.front())
                      : fmt::format("element assembly on 1 MPI rank: {} elements, {:.4f} s",
                                    elements_.size(), seconds.front());
  auto count = [&](const std::vector<char>& flags) {
    return static_cast<double>(std::count(flags.begin(), flags.end(), 1));
  };
  const std::vector<double> owned = values_of_all_ranks(
      static_cast<double>(std::count(element_owner_.begin(), element_owner_.end(), rank_)));
  const std::vector<double> evaluated = values_of_all_ranks(count(evaluate_vectors_));
  const std::vector<double> matrix = values_of_all_ranks(count(evaluate_matrix_));
  auto join = [](const std::vector<double>& x, const char* format) {
    std::string out;
    for (std::size_t r = 0; r < x.size(); ++r)
      out += (r > 0 ? " + " : "") + fmt::format(fmt::runtime(format), x[r]);
    return out;
  };
  double total = 0.0;
  for (double o : owned) total += o;
  return fmt::format(
      "element assembly split over {} MPI ranks (METIS column partition): owned {} = {:.0f} of "
      "{} elements; evaluated for the matrix {}, for the force vectors {} (owned plus "
      "neighbours); element assembly seconds per rank {} (CPU {})",
      ranks_, join(owned, "{:.0f}"), total, elements_.size(), join(matrix, "{:.0f}"),
      join(evaluated, "{:.0f}"), join(seconds, "{:.4f}"), join(cpu, "{:.4f}"));
}

void Assembler::assemble(const IntegrationCoefficients& coeff, const VectorXd& u, const VectorXd& v,
                         const Output& out, const VectorXd* a) const {
  const auto start = std::chrono::steady_clock::now();
  // The CPU clock is a system call (not a vDSO read): only an MPI run reports it.
  const bool timed = ranks_ > 1;
  const std::clock_t cpu_start = timed ? std::clock() : 0;
  const bool split = !dof_owner_.empty();
  const bool vectors = out.internal_force || out.damping_force || out.inertia_force;
  const std::vector<char>* only = !split    ? nullptr
                                  : vectors ? &evaluate_vectors_
                                            : &evaluate_matrix_;
  compute_nonlinear_tangents(u, out.effective != nullptr, only,
                             out.tangent_follows && out.effective == nullptr);
  add_forces(u, v, a, out, only);
  if (out.effective) {
    // Swapped in, not assigned: Eigen 3.4 copies a SparseMatrix on assignment, briefly twice.
    if (out.effective->nonZeros() != pattern_nonzeros_)
      pattern().zero_matrix().swap(*out.effective);
    double* values = out.effective->valuePtr();
    VectorXd ue;
    MatrixXd c;
    // The part that does not change within a time step (the linear elements' cK K + cC C and
    // every element's cM M) from its cache, then the nonlinear elements' cK K_T (+ cC C);
    // distributed, only those at this rank's columns (the other columns are never read).
    const std::vector<double>& constant = constant_effective(coeff);
    std::copy(constant.begin(), constant.end(), values);
    for (std::size_t e : nonlinear_) {
      if (split && !evaluate_matrix_[e]) continue;
      const MatrixXd& ke = tangent_buffer_[e];
      bool damped = false;
      if (coeff.cC != 0.0) {
        gather(e, u, ue);
        damped = element_damping(e, ue, ke, mass_[e], c);
      }
      scatter_lower(e, coeff.cK, ke, damped ? coeff.cC : 0.0, damped ? &c : nullptr, values);
    }
  }
  element_seconds_ +=
      std::chrono::duration<double>(std::chrono::steady_clock::now() - start).count();
  if (timed) element_cpu_seconds_ += static_cast<double>(std::clock() - cpu_start) / CLOCKS_PER_SEC;
  // The nonlinear elements' share of the vectors was summed by the owner of each entry only
  // (the linear part and M a come from the global products, the same on every rank).
  if (!split || nonlinear_.empty()) return;
  for (VectorXd* f : {out.internal_force, out.damping_force})
    if (f) share_owned_values(f->data(), static_cast<int>(f->size()), dof_owner_);
}

void Assembler::add_forces(const VectorXd& u, const VectorXd& v, const VectorXd* a,
                           const Output& out, const std::vector<char>* only) const {
  // The linear elements and the mass from the stored global products; the nonlinear elements
  // from the buffers of the tangent phase (their damping, which may depend on u, element by
  // element).
  IMPACTFE_CHECK(out.inertia_force == nullptr || a != nullptr,
                 "Assembler: the inertia force needs the acceleration");
  linear_products_.multiply({&u, &v, a},
                            {out.internal_force, out.damping_force, out.inertia_force});
  MatrixXd c;
  VectorXd ue, ve, fd;
  for (std::size_t e : nonlinear_) {
    if (only && !(*only)[e]) continue;
    const auto& idx = dofs_.element_indices(e);
    const int n = static_cast<int>(idx.size());
    if (out.internal_force)
      for (int k = 0; k < n; ++k) (*out.internal_force)(idx[k]) += force_buffer_[e](k);
    if (!out.damping_force) continue;
    gather(e, u, ue);
    if (!element_damping(e, ue, tangent_buffer_[e], mass_[e], c)) continue;
    gather(e, v, ve);
    fd.noalias() = c * ve;
    for (int k = 0; k < n; ++k) (*out.damping_force)(idx[k]) += fd(k);
  }
}

VectorXd Assembler::inertia_force(const VectorXd& a) const {
  VectorXd f;
  inertia_force(a, f);
  return f;
}

void Assembler::inertia_force(const VectorXd& a, VectorXd& f) const {
  linear_products_.multiply({nullptr, nullptr, &a}, {nullptr, nullptr, &f});
}

void Assembler::compute_nonlinear_tangents(const VectorXd& u, bool with_tangent,
                                           const std::vector<char>* only,
                                           bool tangent_follows) const {
  // Tangents of the nonlinear elements (the expensive part: co-rotational shells,
  // total-Lagrangian bricks) into per-element buffers. Elements are const here and keep no shared
  // scratch, so the loop is race-free and its results do not depend on the thread count; the
  // scatter that follows stays serial and deterministic.
  const int n_nonlinear = static_cast<int>(nonlinear_.size());
  auto needed = [&](int i) { return !only || (*only)[nonlinear_[static_cast<std::size_t>(i)]]; };
  // Ahead of a factorization, only the elements whose buffers it can reuse form their tangents
  // (and, distributed, only those at this rank's matrix columns): the others are evaluated
  // again by it anyway.
  const bool split = !dof_owner_.empty();
  auto tangent_of = [&](std::size_t e) {
    return with_tangent ||
           (tangent_follows && reusable_[e] && (!split || evaluate_matrix_[e] != 0));
  };
  auto evaluate = [&](int i) {
    const std::size_t e = nonlinear_[static_cast<std::size_t>(i)];
    return needed(i) && evaluate_tangent(e, u, tangent_of(e));
  };
  const bool after_ahead = threading_.formed_ahead;
  threading_.formed_ahead = tangent_follows && !with_tangent;
  if (threading_.parallel) {
    // An element's exception (e.g. one that collapsed under large deflection) comes back from
    // the loop as the one of the lowest element index, the one the serial loop would throw.
    threads::parallel_for(n_nonlinear, 8, [&](int i) { evaluate(i); });
    return;
  }
  const auto start = std::chrono::steady_clock::now();
  int evaluated = 0, wanted = 0;
  for (int i = 0; i < n_nonlinear; ++i) {
    wanted += needed(i) ? 1 : 0;
    evaluated += evaluate(i) ? 1 : 0;
  }
  // The probes estimate a full pass: a pass that reused some buffers is scaled to all the
  // elements it wanted (elements that never move, e.g. on constrained nodes, reuse theirs at
  // every pass), and one that evaluated nothing is no probe; nor is one of forces alone, nor
  // the factorization's pass after tangents formed ahead (it evaluates the elements with a
  // status or history alone, whose cost says nothing of the others').
  if (evaluated > 0 && (with_tangent || tangent_follows) && !(with_tangent && after_ahead))
    threading_.record_serial_pass(
        std::chrono::duration<double>(std::chrono::steady_clock::now() - start).count() * wanted /
        evaluated);
}

bool Assembler::evaluate_tangent(std::size_t e, const VectorXd& u, bool with_tangent) const {
  // The element's own scratch for its gathered values: a pass allocates nothing once every
  // element has been evaluated (a fresh vector per evaluation was a third of the thesis
  // helmet's 2e5 allocations, issue 11).
  VectorXd& ue = gathered_[e];
  gather(e, u, ue);
  VectorXd& at = tangent_at_[e];
  if (reusable_[e] && buffers_at_[e] && (tangent_valid_[e] || !with_tangent) &&
      at.size() == ue.size() &&
      std::memcmp(at.data(), ue.data(), sizeof(double) * static_cast<std::size_t>(ue.size())) == 0)
    return false;
  buffers_at_[e] = 0;  // the buffers are not reusable until the evaluation has succeeded
  // Rayleigh β K_e damping forces read the tangent: such elements always form it.
  const bool tangent =
      with_tangent || damping_reads_tangent(e) || !elements_[e]->separate_internal_force(ctx_);
  if (tangent)
    elements_[e]->tangent(ctx_, ue, tangent_buffer_[e], force_buffer_[e]);
  else
    elements_[e]->internal_force(ctx_, ue, force_buffer_[e]);
  tangent_valid_[e] = static_cast<char>(tangent);
  if (reusable_[e]) {
    at.swap(ue);  // the next gather overwrites the old values in place
    buffers_at_[e] = 1;
  }
  return true;
}

void Assembler::TangentThreading::record_serial_pass(double seconds) {
  if (probes_left == 0) return;
  fastest_serial_seconds = std::min(fastest_serial_seconds, seconds);
  if (--probes_left > 0) return;
  parallel = threads::max_threads() > 1 && fastest_serial_seconds >= kMinParallelSeconds;
}

bool Assembler::element_damping(std::size_t e, const VectorXd& ue, const MatrixXd& k,
                                const MatrixXd& m, MatrixXd& c) const {
  const Element& element = *elements_[e];
  const double beta = beta_of(e);  // global BETAD plus the material's MP,DAMP
  const bool rayleigh = alpha_ != 0.0 || beta != 0.0;
  if (own_damping(e)) {
    own_damping_matrix(e, ue, k, m, c);
  } else if (rayleigh) {
    c.setZero(element.n_dofs(), element.n_dofs());
  } else {
    return false;
  }
  // k is read only with a β ≠ 0 (damping_reads_tangent: otherwise a forces-only pass leaves the
  // tangent buffer stale).
  if (beta != 0.0)
    c += alpha_ * m + beta * k;
  else if (rayleigh)
    c += alpha_ * m;
  return true;
}

template <class Visit>
void Assembler::for_each_lower_product_entry(Visit&& visit) const {
  // Symmetric storage keeps each row from its group's first row on: the stored (r, j) with
  // r <= j is the lower entry (j, r), visited by rows r, i.e. column by column of the lower
  // triangle (the mirrored entries inside a group's own block are skipped). Otherwise every
  // entry is stored and the lower ones (r >= j) are visited row by row.
  const bool symmetric = linear_products_.symmetric();
  linear_products_.for_each_stored_entry([&](int r, int j, const double* v) {
    if (symmetric ? r > j : r < j) return;
    if (symmetric)
      visit(j, r, v);
    else
      visit(r, j, v);
  });
}

const std::vector<double>& Assembler::constant_effective(
    const IntegrationCoefficients& coeff) const {
  if (!constant_effective_.empty() && constant_coeff_.cK == coeff.cK &&
      constant_coeff_.cC == coeff.cC && constant_coeff_.cM == coeff.cM)
    return constant_effective_;
  const SparsePattern& p = pattern();
  constant_effective_.assign(static_cast<std::size_t>(p.nonzeros()), 0.0);
  add_constant_effective(coeff, p.column_start.data(), p.row.data(), constant_effective_.data());
  constant_coeff_ = coeff;
  return constant_effective_;
}

const SparsePattern& Assembler::pattern() const {
  if (pattern_.row.empty() && pattern_nonzeros_ > 0) {
    pattern_ = DofGraph(dofs_, elements_.size()).lower_pattern(dofs_.n_free());
    IMPACTFE_CHECK(pattern_.nonzeros() == pattern_nonzeros_,
                   "Assembler: the pattern formed again differs from the first");
  }
  return pattern_;
}

void Assembler::add_constant_effective(const IntegrationCoefficients& coeff, const int* outer,
                                       const int* inner, double* values) const {
  // cK K_L + cC C_L + cM M from the global products (the element matrices are not kept), into
  // the free-free lower pattern. Within a column the rows ascend, as in the pattern, so a slot
  // is found by continuing the previous one's search; a new column starts a binary search.
  const int nf = dofs_.n_free();
  const double factor[3] = {coeff.cK, coeff.cC, coeff.cM};
  int last_row = -1, last_column = -1, at = 0;
  for_each_lower_product_entry([&](int row, int column, const double* v) {
    if (row >= nf) return;  // column <= row: free too
    if (column == last_column && row > last_row) {
      while (at < outer[column + 1] && inner[at] < row) ++at;
    } else {
      at = static_cast<int>(
          std::lower_bound(inner + outer[column], inner + outer[column + 1], row) - inner);
    }
    last_row = row;
    last_column = column;
    IMPACTFE_CHECK(at < outer[column + 1] && inner[at] == row,
                   "Assembler: a product entry outside the element pattern");
    values[at] += factor[0] * v[0] + factor[1] * v[1] + factor[2] * v[2];
  });
}

VectorXd Assembler::mass_diagonal() const {
  VectorXd d = VectorXd::Zero(dofs_.n_active());
  for_each_lower_product_entry([&](int row, int column, const double* v) {
    if (row == column) d(row) = v[2];
  });
  return d;
}

SparseMatrix Assembler::mass_block_lower(const std::vector<int>& position, int size) const {
  const auto position_of = [&](int i) {
    return static_cast<std::size_t>(i) < position.size() ? position[static_cast<std::size_t>(i)]
                                                         : -1;
  };
  std::vector<Eigen::Triplet<double, int>> triplets;
  for_each_lower_product_entry([&](int row, int column, const double* v) {
    if (v[2] == 0.0) return;
    const int pr = position_of(row), pc = position_of(column);
    if (pr < 0 || pc < 0) return;
    // Renumbering may turn an entry over the diagonal: keep it in the lower triangle.
    triplets.emplace_back(std::max(pr, pc), std::min(pr, pc), v[2]);
  });
  SparseMatrix block(size, size);
  block.setFromTriplets(triplets.begin(), triplets.end());
  return block;
}

void Assembler::scatter_lower(std::size_t e, double a_factor, const MatrixXd& a, double b_factor,
                              const MatrixXd* b, double* values) const {
  const double* av = a.data();
  if (b) {
    const double* bv = b->data();
    for (const ScatterEntry& entry : scatter_[e])
      values[entry.slot] += a_factor * av[entry.element_entry] + b_factor * bv[entry.element_entry];
    return;
  }
  for (const ScatterEntry& entry : scatter_[e])
    values[entry.slot] += a_factor * av[entry.element_entry];
}

std::vector<int> Assembler::nonlinear_free_dofs() const {
  std::vector<int> out;
  for (std::size_t e : nonlinear_)
    for (int i : dofs_.element_indices(e))
      if (i < dofs_.n_free()) out.push_back(i);
  std::sort(out.begin(), out.end());
  out.erase(std::unique(out.begin(), out.end()), out.end());
  return out;
}

void Assembler::assemble_linear_part(const IntegrationCoefficients& coeff,
                                     SparseMatrix& effective) const {
  // Not through the cache of constant_effective: the condensed transient factors this once per
  // time step size and would only keep a second copy of its values.
  if (effective.nonZeros() != pattern_nonzeros_) pattern().zero_matrix().swap(effective);
  std::fill(effective.valuePtr(), effective.valuePtr() + effective.nonZeros(), 0.0);
  add_constant_effective(coeff, effective.outerIndexPtr(), effective.innerIndexPtr(),
                         effective.valuePtr());
  // The matrix holds the structure now; the pattern is formed again if a full assembly needs it
  // (issue 11: 18 MB beside the factor on the 155 522-DOF dome).
  pattern_ = SparsePattern{};
}

void Assembler::assemble_nonlinear_part(const IntegrationCoefficients& coeff, double w,
                                        const VectorXd& u, const VectorXd& v,
                                        const std::vector<int>& position, VectorXd& phi,
                                        MatrixXd* tangent) const {
  compute_nonlinear_tangents(u, tangent != nullptr);
  MatrixXd c;
  VectorXd ue, ve, fe;
  for (std::size_t e : nonlinear_) {
    const auto& idx = dofs_.element_indices(e);
    const int n = static_cast<int>(idx.size());
    const MatrixXd& k = tangent_buffer_[e];
    fe = force_buffer_[e];
    gather(e, u, ue);
    const bool damped = element_damping(e, ue, k, mass_[e], c);
    if (damped) {
      gather(e, v, ve);
      fe += c * ve;
    }
    for (int a = 0; a < n; ++a) {
      const int pa = position[static_cast<std::size_t>(idx[a])];
      if (pa < 0) continue;
      phi(pa) += w * fe(a);
      if (!tangent) continue;
      for (int b = 0; b < n; ++b) {
        const int pb = position[static_cast<std::size_t>(idx[b])];
        if (pb < 0) continue;
        (*tangent)(pa, pb) += coeff.cK * k(a, b) + (damped ? coeff.cC * c(a, b) : 0.0);
      }
    }
  }
}

SparseMatrix Assembler::full_matrix(Which which, const VectorXd& u) const {
  // The linear elements' matrices are evaluated again here (the assembler keeps only their
  // global products): these matrices are asked for once per analysis (energies, reduction,
  // mode superposition), and element by element they keep the structure and the values of
  // the element-order sum bit for bit.
  const DofGraph graph(dofs_, elements_.size());
  GraphMatrix out(graph);
  std::vector<int> slots;
  MatrixXd m, k, mass;
  VectorXd ue, fe;
  for (std::size_t e = 0; e < elements_.size(); ++e) {
    const auto& idx = dofs_.element_indices(e);
    const int n = static_cast<int>(idx.size());
    const MatrixXd* element_matrix = &m;  // the stored matrix where there is one (no copy)
    switch (which) {
      case Which::Mass:
        if (is_linear_[e])
          elements_[e]->mass(ctx_, m);
        else
          element_matrix = &mass_[e];
        break;
      case Which::Stiffness:
        if (is_linear_[e]) {
          linear_element_stiffness(e, m);
        } else {
          gather(e, u, ue);
          elements_[e]->tangent(ctx_, ue, m, fe);
        }
        break;
      case Which::Damping: {
        const double beta = beta_of(e);
        const bool rayleigh = alpha_ != 0.0 || beta != 0.0;
        if (!own_damping(e) && !rayleigh) continue;
        gather(e, u, ue);
        if (own_damping(e)) {
          // The element's mass and tangent at ue for its material's α M_e + β K_e.
          const Element::MaterialDamping& d = elements_[e]->material_damping();
          if (d.alpha != 0.0) elements_[e]->mass(ctx_, mass);
          if (d.beta != 0.0) elements_[e]->tangent(ctx_, ue, k, fe);
          own_damping_matrix(e, ue, k, mass, m);
        } else {
          m.setZero(n, n);
        }
        if (rayleigh) {
          if (is_linear_[e]) {
            linear_element_matrices(e, k, mass);
          } else {
            elements_[e]->tangent(ctx_, ue, k, fe);
            mass = mass_[e];
          }
          m += alpha_ * mass + beta * k;
        }
        break;
      }
    }
    graph.element_slots(idx, slots);
    out.add(slots, *element_matrix, true);
  }
  return out.to_sparse(graph);
}

bool Assembler::is_nonlinear() const {
  return std::any_of(is_linear_.begin(), is_linear_.end(), [](bool linear) { return !linear; });
}

SparseMatrix Assembler::mass_matrix() const {
  return full_matrix(Which::Mass, VectorXd());
}
SparseMatrix Assembler::stiffness_matrix(const VectorXd& u) const {
  return full_matrix(Which::Stiffness, u);
}
SparseMatrix Assembler::damping_matrix(const VectorXd& u) const {
  return full_matrix(Which::Damping, u);
}

}  // namespace impactfe
