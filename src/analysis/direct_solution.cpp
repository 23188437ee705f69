#include "analysis/direct_solution.h"

#include <algorithm>
#include <cmath>
#include <utility>

#include "core/log.h"
#include "linalg/mass_solve.h"
#include "time/time_axis.h"

namespace impactfe {

namespace {

/// Remaps a state vector from one DOF numbering to another (by DOF key).
VectorXd remap(const VectorXd& values, const DofMap& from, const DofMap& to) {
  VectorXd out = VectorXd::Zero(to.n_active());
  if (values.size() == 0) return out;
  for (int i = 0; i < to.n_active(); ++i) {
    const int j = from.index(to.key(i));
    if (j >= 0) out(i) = values(j);
  }
  return out;
}

}  // namespace

DirectSolution::DirectSolution(Structure& structure, ResultsWriter& writer,
                               const RunSettings& settings, AnalysisStatistics& stats)
    : structure_(structure),
      writer_(writer),
      settings_(settings),
      stats_(stats),
      ctx_(structure.context()),
      energy_(std::make_unique<EnergyBalance>(structure.elements())) {}

void DirectSolution::set_constraints(const LoadStep& step) {
  std::set<DofKey> wanted = structure_.constraints_of(step);
  if (dofs_ && wanted == constrained_) return;
  renumber(std::move(wanted), false);
}

void DirectSolution::renumber(std::set<DofKey> wanted, bool keep_dynamics) {
  auto dofs = std::make_unique<DofMap>(structure_.elements(), wanted);
  if (dofs_) {
    u_ = remap(u_, *dofs_, *dofs);
    v_ = remap(v_, *dofs_, *dofs);
    a_ = remap(a_, *dofs_, *dofs);
    f_ext_old_ = remap(f_ext_old_, *dofs_, *dofs);
    f_int_old_ = remap(f_int_old_, *dofs_, *dofs);
    f_damp_old_ = remap(f_damp_old_, *dofs_, *dofs);
    reactions_ = remap(reactions_, *dofs_, *dofs);
    inertia_a_ = VectorXd();  // the cached M a belongs to the old numbering
    if (keep_dynamics && dynamics_started_ && integrator_)
      remap_integrator(*dofs_, *dofs);
    else
      dynamics_started_ = false;  // the integrator history belongs to the old numbering
  } else {
    u_ = VectorXd::Zero(dofs->n_active());
    v_ = VectorXd::Zero(dofs->n_active());
    a_ = VectorXd::Zero(dofs->n_active());
    // Initial conditions (IC): displacement and velocity at t = 0.
    for (const auto& [key, ic] : structure_.model().initial_conditions) {
      const int i = dofs->index(key);
      if (i < 0) continue;
      u_(i) = ic.displacement;
      v_(i) = ic.velocity;
    }
    f_ext_old_ = f_int_old_ = f_damp_old_ = VectorXd::Zero(dofs->n_active());
  }
  constrained_ = std::move(wanted);
  dofs_ = std::move(dofs);
  assembler_ = std::make_unique<Assembler>(structure_.elements(), *dofs_, ctx_,
                                           structure_.options().alpha_damping,
                                           structure_.options().beta_damping);
  assembler_->set_material_stiffness_damping(structure_.material_stiffness_damping());
  status_loop_ = std::make_unique<StatusLoop>(structure_.elements(), *assembler_);
  penetration_checks_.clear();
  for (std::size_t e = 0; e < structure_.elements().size(); ++e)
    if (const auto* check = dynamic_cast<const PenetrationCheck*>(structure_.elements()[e].get());
        check != nullptr && check->checks_penetration())
      penetration_checks_.emplace_back(e, check);
  frame_load_ = FrameAccelerationLoad(structure_.elements(), *dofs_, ctx_);
  // Keep the work of the previous numbering in the counts.
  if (solver_) retired_ += solver_->counters();
  if (condensation_) retired_ += condensation_->counters();
  solver_ = make_linear_solver(dofs_->n_free());
  // Formed on the first full assembly (a condensed transient may never need it).
  SparseMatrix().swap(effective_);  // freed (assigning an empty matrix keeps the storage)
  // A solver that reads only some columns on this rank (MUMPS on several ranks): the assembler
  // then evaluates only the elements at them (docs/scaling.md, "Element assembly split by rank").
  assembler_->distribute(solver_->column_owners(assembler_->pattern().zero_matrix()));
  factor_valid_ = false;
  stats_.n_dofs = dofs_->n_free();
  condensation_.reset();
  contact_frequency_.reset();
  if (!status_loop_->empty())
    contact_frequency_ = std::make_unique<ContactFrequencyEstimator>(
        structure_.elements(), *dofs_,
        assembler_->inertia_force(VectorXd::Ones(dofs_->n_active())));
  if (transient_ && settings_.condense && assembler_->n_nonlinear_elements() > 0) {
    if (const auto why = LinearPartCondensation::refusal(*assembler_)) {
      condensation_note_ = "condensed transient not used: " + *why;
    } else {
      condensation_ = std::make_unique<LinearPartCondensation>(*assembler_);
      condensation_note_ = fmt::format(
          "condensed transient: the linear part ({} free DOFs) is factorized once per time step "
          "size and condensed onto the {} DOFs of the {} nonlinear elements",
          dofs_->n_free(), condensation_->size(), assembler_->n_nonlinear_elements());
    }
  }
}

VectorXd DirectSolution::external_force(const LoadPoint& at) const {
  VectorXd f;
  external_force(at, f);
  return f;
}

void DirectSolution::external_force(const LoadPoint& at, VectorXd& f) const {
  frame_load_.assign(frame_acceleration(at), dofs_->n_active(), f);
  if (at.current == resolved_step_) {
    forces_.add_to(at, f);
  } else {
    f += nodal_forces(*dofs_, at);
  }
  if (!at.current->pressures.empty())
    f += pressure_forces(structure_.elements(), *dofs_, ctx_, at, u_);
}

LoadPoint DirectSolution::load_point(const LoadStep& step, const LoadStep* previous,
                                     double fraction, double time) const {
  return LoadPoint{&step, previous, fraction, time, &structure_.model().time_functions};
}

void DirectSolution::factorize(const IntegrationCoefficients& coeff, const VectorXd& u) {
  assembler_->assemble(coeff, u, v_, Assembler::Output{&effective_, nullptr, nullptr});
  try {
    if (!factor_valid_ && solver_->counters().analyses == 0) solver_->analyze_pattern(effective_);
    solver_->factorize(effective_);
  } catch (const SingularMatrixError& e) {
    const std::string dof = structure_.describe_dof(*dofs_, e.column());
    // With plasticity a tangent that was regular before (the count includes this attempt) can
    // lose its stiffness: perfectly plastic (Et = 0) parts forming a mechanism, i.e. a load
    // above the collapse load.
    if (status_loop_->has_history() && solver_->counters().factorizations > 1)
      throw SolutionError(fmt::format(
          "load step {} substep {} (t = {:g}): the tangent stiffness became singular at {} "
          "({}): the plastic elements form a mechanism (the load exceeds the collapse load, or "
          "perfectly plastic parts (Et = 0) yield together in one iteration); use smaller load "
          "increments (NSUBST) or a hardening tangent modulus",
          increment_.label.load_step, increment_.label.substep, increment_.label.time, dof,
          elements_at(e.column())));
    if (coeff.cM != 0.0)
      throw ModelError(fmt::format(
          "the effective matrix K + cC C + cM M of the time step is singular at {} (zero pivot, "
          "{}): it has neither stiffness nor mass there; constrain it with D, connect it to the "
          "structure or give it mass",
          dof, elements_at(e.column())));
    throw ModelError(
        fmt::format("the model is singular: {} is unrestrained (zero pivot in the stiffness "
                    "matrix, {}); constrain it with D or connect it to the structure",
                    dof, elements_at(e.column())));
  }
  // A negative pivot of a dynamic effective matrix: the tangent stiffness is negative there
  // (compressive stress stiffening, buckling) by more than the inertia term cM M holds, so the
  // step may leave the stable path.
  if (coeff.cM != 0.0 && solver_->negative_pivots() > 0 && !negative_pivot_warned_) {
    negative_pivot_warned_ = true;
    const int row = solver_->first_negative_pivot_row();
    Log::warn(
        "load step {} substep {} (t = {:g}): the effective matrix K + cC C + cM M has {} negative "
        "pivot(s), the first at {} ({}): the tangent stiffness there is negative (compression, "
        "buckling) beyond what the inertia of the time step holds; the solution may follow an "
        "unstable path. Use a smaller time step (DELTIM / DTIME)",
        increment_.label.load_step, increment_.label.substep, increment_.label.time,
        solver_->negative_pivots(), row >= 0 ? structure_.describe_dof(*dofs_, row) : "?",
        row >= 0 ? elements_at(row) : "?");
  }
  factor_valid_ = true;
  factored_ = coeff;
}

std::string DirectSolution::excessive_penetration(const VectorXd& u) const {
  double worst = 1.0;
  std::size_t at = 0;
  VectorXd ue, start;
  for (const auto& [e, check] : penetration_checks_) {
    assembler_->gather(e, u, ue);
    assembler_->gather(e, u_, start);
    const double ratio = check->penetration_ratio(start, ue);
    if (ratio > worst) {
      worst = ratio;
      at = e;
    }
  }
  if (worst <= 1.0) return {};
  return fmt::format(
      "contact element {} penetrated {:.3g} x FTOLN x depth further in one substep (KEYOPT(7) = 1)",
      structure_.elements()[at]->id(), worst);
}

void DirectSolution::start_dynamics(const LoadPoint& at, double h) {
  // a0 from equilibrium at the start: M a0 = f(0) - C v0 - f_int(u0), on DOFs that carry mass
  // (spec §10.2); massless DOFs get a0 = 0.
  const int nf = dofs_->n_free();
  VectorXd f_int, f_damp;
  assembler_->assemble({}, u_, v_, Assembler::Output{nullptr, &f_int, &f_damp});
  const VectorXd f0 = external_force(at);
  const VectorXd rhs = f0 - f_int - f_damp;
  std::vector<int> massive;
  const VectorXd mass_diagonal = assembler_->mass_diagonal();
  for (int i = 0; i < nf; ++i)
    if (mass_diagonal(i) > 0.0) massive.push_back(i);
  a_.setZero();
  if (!massive.empty()) {
    const int nm = static_cast<int>(massive.size());
    std::vector<int> position(static_cast<std::size_t>(nf), -1);
    for (int k = 0; k < nm; ++k) position[static_cast<std::size_t>(massive[k])] = k;
    const SparseMatrix mm = assembler_->mass_block_lower(position, nm);
    VectorXd r(nm);
    for (int k = 0; k < nm; ++k) r(k) = rhs(massive[k]);
    const VectorXd am = solve_mass_system(mm, r).a;
    for (int k = 0; k < nm; ++k) a_(massive[k]) = am(k);
  }
  integrator_->start(u_, v_, a_, h);
  f_ext_old_ = f0;
  f_int_old_ = f_int;
  f_damp_old_ = f_damp;
  dynamics_started_ = true;
  factor_valid_ = false;
}

void DirectSolution::run(const std::vector<LoadStep>& steps, bool transient) {
  begin(transient);
  for (std::size_t i = 0; i < steps.size(); ++i) {
    set_following_steps({steps.begin() + static_cast<long>(i) + 1, steps.end()});
    solve_load_step(steps[i]);
  }
  finish();
}

void DirectSolution::set_following_steps(std::vector<LoadStep> steps) {
  following_ = std::move(steps);
}

void DirectSolution::begin(bool transient) {
  transient_ = transient;
  if (transient) integrator_ = make_time_integrator(structure_.options());
  take_restart_request();
}

std::string DirectSolution::condensed_tangent_note() const {
  if (!condensation_) return "";
  const UpdatableDenseFactor& f = condensation_->tangent_factor();
  if (f.full_factorizations() == 0) return "";
  return fmt::format("; the condensed tangent: {} factorization(s), {} rank-one update(s)",
                     f.full_factorizations(), f.rank_one_updates());
}

void DirectSolution::finish() {
  if (!condensation_note_.empty())
    stats_.notes.push_back(condensed_steps_ + full_fallback_steps_ > 0
                               ? fmt::format("{}; {} steps condensed, {} finished by full Newton{}",
                                             condensation_note_, condensed_steps_,
                                             full_fallback_steps_, condensed_tangent_note())
                               : condensation_note_);
  if (transient_) {
    const double kinetic = kinetic_energy();
    stats_.notes.push_back(energy_->summary(time_, kinetic));
    if (const auto warning = energy_->balance_warning(kinetic)) Log::warn("{}", *warning);
  }
  if (solver_ && solver_->name() == "MUMPS") stats_.notes.push_back(assembler_->assembly_summary());
  if (renumberings_ > 0)
    stats_.notes.push_back(fmt::format(
        "large sliding: the contact DOF lists changed after {} of {} accepted steps (DOFs "
        "renumbered then)",
        renumberings_, refresh_passes_));
  update_counters();
}

void DirectSolution::update_counters() {
  SolverCounters now = solver_ ? solver_->counters() : SolverCounters{};
  if (condensation_) now += condensation_->counters();
  SolverCounters total = retired_;
  total += now;
  record_solver_counters(stats_, total);
}

int DirectSolution::n_unknowns() const {
  return dofs_->n_free();
}

double DirectSolution::residual(const VectorXd& u, VectorXd& r, double& reference) {
  Increment& inc = increment_;
  const int nf = dofs_->n_free();
  const bool tangent_follows = std::exchange(tangent_expected_, false);
  if (inc.dynamic) integrator_->kinematics(u, inc.v, inc.a);
  if (inc.follower) {
    // Follower pressure (large deflection): the load of the deformed faces at this iterate. Its
    // load stiffness is left out of the tangent (it is unsymmetric and the solvers are
    // symmetric), so Newton converges linearly on this part.
    const VectorXd fp = pressure_forces(structure_.elements(), *dofs_, ctx_, inc.at, u);
    const VectorXd delta = fp - inc.f_pressure;
    inc.f_pressure = fp;
    inc.f_ext += delta;
    if (inc.dynamic) inc.fixed_terms += inc.weights.external * delta;
  }
  if (inc.dynamic) {
    assembler_->assemble(
        inc.coeff, u, inc.v,
        Assembler::Output{nullptr, &inc.f_int, &inc.f_damp, &inc.inertia, tangent_follows}, &inc.a);
    inertia_a_ = inc.a;
    inertia_ = inc.inertia;
    r = inc.fixed_terms - inc.weights.inertia * inc.inertia -
        inc.weights.stiffness * (inc.f_int + inc.f_damp);
    reference = std::max(
        {inc.f_ext.head(nf).norm(), inc.inertia.head(nf).norm(), inc.f_int.head(nf).norm()});
  } else {
    assembler_->assemble(
        inc.coeff, u, inc.v,
        Assembler::Output{nullptr, &inc.f_int, &inc.f_damp, nullptr, tangent_follows});
    r = inc.f_ext - inc.f_int;
    reference = std::max(inc.f_ext.head(nf).norm(), inc.f_int.head(nf).norm());
  }
  return r.head(nf).norm();
}

bool DirectSolution::update_status(const VectorXd& u) {
  const int changed = status_loop_->update(u, increment_.label);
  if (changed == 0) return false;
  increment_.n_status_changes += changed;
  factor_valid_ = false;
  return true;
}

namespace {

/// The c part of a step of the condensed transient (linear_part_condensation.h): unknowns δ_c,
/// residual ρ = S (y − δ_c) − [φ(δ_c) − φ(0)], tangent S + cK K_N + cC C_N. The nonlinear elements
/// see the full state u0 + E δ_c (and v0 + (cC/wk) E δ_c: v is affine in u with that slope).
/// `u` and `v` are the step's full state, changed in place on c only (the values at the
/// predictor are kept for c alone: a step copies no vector of model size, issue 11).
class CondensedIncrement final : public NonlinearProblem {
 public:
  CondensedIncrement(const Assembler& assembler, LinearPartCondensation& condensation,
                     StatusLoop& status_loop, const StepLabel& label,
                     const IntegrationCoefficients& coeff, double wk, VectorXd& u, VectorXd& v,
                     VectorXd y, double reference)
      : assembler_(assembler),
        condensation_(condensation),
        status_loop_(status_loop),
        label_(label),
        coeff_(coeff),
        wk_(wk),
        u_(u),
        v_(v),
        u0_c_(condensation.size()),
        v0_c_(condensation.size()),
        y_(std::move(y)),
        reference_(reference),
        phi0_(VectorXd::Zero(condensation.size())) {
    const auto& c = condensation_.dofs();
    for (std::size_t k = 0; k < c.size(); ++k) {
      u0_c_(static_cast<Eigen::Index>(k)) = u_(c[k]);
      v0_c_(static_cast<Eigen::Index>(k)) = v_(c[k]);
    }
    assembler_.assemble_nonlinear_part(coeff_, wk_, u_, v_, condensation_.position(), phi0_,
                                       nullptr);
  }
  /// u on c at the predictor.
  const VectorXd& u0_c() const { return u0_c_; }

  int n_unknowns() const override { return condensation_.size(); }
  double residual(const VectorXd& delta, VectorXd& r, double& reference) override {
    set_state(delta);
    VectorXd phi = VectorXd::Zero(n_unknowns());
    assembler_.assemble_nonlinear_part(coeff_, wk_, u_, v_, condensation_.position(), phi, nullptr);
    r = condensation_.schur() * (y_ - delta) - (phi - phi0_);
    reference = reference_;
    return r.norm();
  }
  bool tangent_stale() const override { return stale_; }
  void factorize_tangent(const VectorXd& delta) override {
    set_state(delta);
    MatrixXd tangent = condensation_.schur();
    VectorXd phi = VectorXd::Zero(n_unknowns());
    assembler_.assemble_nonlinear_part(coeff_, wk_, u_, v_, condensation_.position(), phi,
                                       &tangent);
    // From the factor of the last tangent (earlier in the step or in an earlier step): a gap
    // that opened or closed changes it on its own DOFs only.
    condensation_.tangent_factor().factorize(tangent);
    stale_ = false;
  }
  VectorXd solve(const VectorXd& r) override { return condensation_.tangent_factor().solve(r); }
  bool update_status(const VectorXd& delta) override {
    set_state(delta);
    n_status_changes_ += status_loop_.update(u_, label_);
    if (n_status_changes_ == reported_) return false;
    reported_ = n_status_changes_;
    stale_ = true;
    return true;
  }
  int n_status_changes() const { return n_status_changes_; }

 private:
  void set_state(const VectorXd& delta) {
    const double slope = wk_ != 0.0 ? coeff_.cC / wk_ : 0.0;  // dv/du of the time scheme
    const auto& c = condensation_.dofs();
    for (std::size_t k = 0; k < c.size(); ++k) {
      const auto j = static_cast<Eigen::Index>(k);
      u_(c[k]) = u0_c_(j) + delta(j);
      v_(c[k]) = v0_c_(j) + slope * delta(j);
    }
  }

  const Assembler& assembler_;
  LinearPartCondensation& condensation_;
  StatusLoop& status_loop_;
  StepLabel label_;
  IntegrationCoefficients coeff_;
  double wk_;
  VectorXd& u_;  // full state at the current δ_c
  VectorXd& v_;
  VectorXd u0_c_, v0_c_;  // on c, at the predictor
  VectorXd y_;
  double reference_;
  VectorXd phi0_;
  bool stale_ = true;
  int n_status_changes_ = 0, reported_ = 0;
};

}  // namespace

bool DirectSolution::solve_condensed(VectorXd& u, const NewtonOptions& newton,
                                     NewtonResult& result) {
  Increment& inc = increment_;
  const ConvergenceOptions& conv = structure_.options().convergence;
  try {
    condensation_->prepare(inc.coeff);
  } catch (const SingularMatrixError& e) {
    // A DOF held only by nonlinear elements (no mass, no linear stiffness): full Newton.
    condensation_note_ = fmt::format(
        "condensed transient not used: the linear part alone is singular at {} (held only by "
        "nonlinear elements)",
        describe(dofs_->key(e.column())));
    condensation_.reset();
    return false;
  }
  const int nf = dofs_->n_free();
  VectorXd& r = step_residual_;  // kept: a step allocates no vector of model size (issue 11)
  double reference = 0.0;
  residual(u, r, reference);  // also v(u0) into inc.v
  const VectorXd y = condensation_->condense(r.head(nf));
  const auto& c = condensation_->dofs();
  // The problem moves u and inc.v on c; the residual below forms inc.v again from u.
  CondensedIncrement problem(*assembler_, *condensation_, *status_loop_, inc.label, inc.coeff,
                             inc.weights.stiffness, u, inc.v, y, reference);
  // δ_c = y, the linear part's own answer, is the exact solution when the nonlinear elements
  // add no force there (ρ(y) = 0: gaps that stay open) and keep their statuses: then the step is
  // the linear part's solve alone (free flight).
  VectorXd delta = y;
  VectorXd rho;
  double unused = 0.0;
  const bool inactive =
      problem.residual(delta, rho, unused) == 0.0 && !problem.update_status(delta);
  if (inactive) {
    result = NewtonResult{};
    result.converged = true;
    result.iterations = 1;
  } else {
    delta.setZero();
    result = NewtonRaphson(newton, ConvergenceTest(conv)).solve(problem, delta);
  }
  // The whole field, once: δ_c on c, the linear part's rows in balance elsewhere (u holds the
  // last iterate on c; the predictor's values there are put back before the update).
  const VectorXd& u0_c = problem.u0_c();
  for (std::size_t k = 0; k < c.size(); ++k) u(c[k]) = u0_c(static_cast<Eigen::Index>(k));
  condensation_->recover(delta, step_correction_);
  u.head(nf) += step_correction_;
  inc.n_status_changes += problem.n_status_changes();
  for (std::size_t k = 0; k < c.size(); ++k)
    u(c[k]) = u0_c(static_cast<Eigen::Index>(k)) + delta(static_cast<Eigen::Index>(k));
  // The full criterion on the recovered state (this evaluation also gives the forces the step
  // is accepted with).
  const double residual_norm = this->residual(u, r, reference);
  const ConvergenceTest test(conv);
  if (!result.converged || !test.force_converged(residual_norm, reference)) {
    factor_valid_ = false;  // statuses may have changed since the full tangent was factorized
    ++full_fallback_steps_;
    return false;
  }
  ++condensed_steps_;
  result.residual_norm = residual_norm;
  result.reference = test.reference(reference);
  return true;
}

bool DirectSolution::solve_increment(const LoadPoint& at, const StepLabel& label, bool dynamic,
                                     bool may_cut) {
  const AnalysisOptions& options = structure_.options();
  const ConvergenceOptions& conv = options.convergence;
  const int nc = dofs_->n_constrained();

  Increment& inc = increment_;
  inc.dynamic = dynamic;
  inc.label = label;
  inc.n_status_changes = 0;
  external_force(at, inc.f_ext);  // into the kept vector: no allocation per step (issue 11)
  inc.at = at;
  inc.follower = ctx_.large_deflection && !at.current->pressures.empty();
  if (inc.follower) inc.f_pressure = pressure_forces(structure_.elements(), *dofs_, ctx_, at, u_);
  inc.v = v_;
  inc.a = a_;
  VectorXd& u = step_state_;  // kept: a step allocates no vector of model size (issue 11)
  if (dynamic)
    integrator_->predict(u);
  else
    u = u_;
  u.tail(nc).setZero();  // automatically constrained DOFs (no D) stay at 0
  if (at.current == resolved_step_)
    prescribed_.add_to(at, u);
  else
    u.tail(nc) = prescribed_displacements(*dofs_, at).tail(nc);
  inc.coeff = dynamic ? integrator_->coefficients() : IntegrationCoefficients{1.0, 0.0, 0.0};
  inc.weights = dynamic ? integrator_->weights() : ResidualWeights{};
  if (factor_valid_ && (inc.coeff.cK != factored_.cK || inc.coeff.cC != factored_.cC ||
                        inc.coeff.cM != factored_.cM))
    factor_valid_ = false;
  // Terms of the residual fixed within the step: old-state forces and inertia (generalized-α).
  if (dynamic) {
    const ResidualWeights& w = inc.weights;
    inc.fixed_terms = w.external * inc.f_ext + (1.0 - w.external) * f_ext_old_ -
                      (1.0 - w.inertia) * inertia_of(integrator_->a()) -
                      (1.0 - w.stiffness) * (f_int_old_ + f_damp_old_);
  }

  // The tangent varies with u under large deflection, stress stiffening or plasticity: full
  // Newton re-forms it every `reformulation` iterations (KRF / NROPT); otherwise only a status
  // change does.
  NewtonOptions newton;
  newton.max_iterations = conv.max_iterations;
  newton.full_newton = conv.full_newton;
  newton.reform_every = at.current->reformulation;
  newton.tangent_varies =
      assembler_->is_nonlinear() &&
      (ctx_.large_deflection || ctx_.stress_stiffening || status_loop_->has_history());
  status_loop_->begin_step();
  NewtonResult result;
  try {
    // Follower pressures load the linear part's DOFs through u, which the condensed system
    // does not see: such steps take full Newton.
    const bool condensed =
        dynamic && condensation_ && !inc.follower && solve_condensed(u, newton, result);
    if (!condensed) {
      // Full Newton on all free DOFs (also the fallback when a condensed step left a residual
      // the full criterion does not accept; it starts from the condensed iterate).
      const int before = result.iterations;
      result = NewtonRaphson(newton, ConvergenceTest(conv)).solve(*this, u);
      result.iterations += before;
    }
  } catch (const SolutionError& e) {  // e.g. a plastic mechanism: a smaller step may pass
    status_loop_->end_step();
    if (!may_cut) throw;
    cut_reason_ = e.what();
    status_loop_->revert();
    factor_valid_ = false;
    return false;
  }
  status_loop_->end_step();
  stats_.n_iterations += result.iterations;
  stats_.n_status_changes += inc.n_status_changes;

  const bool finite = result.finite && u.head(dofs_->n_free()).allFinite();
  // A contact that opened or closed within a step longer than the impact limit (T/30 of the
  // contact frequency): the impact is not resolved, so the step is cut like a failed one.
  const double h = dynamic ? integrator_->step() : 0.0;
  const bool unresolved_impact = may_cut && inc.n_status_changes > 0 && impact_step_limit_ > 0.0 &&
                                 h > impact_step_limit_ * (1 + 1e-9);
  // KEYOPT(7) = 1 contact (APDL_MODELING §9.3 item 2): penetration > FTOLN·depth cuts too.
  const std::string penetration =
      may_cut && finite && result.converged && !status_loop_->chattered() && !unresolved_impact
          ? excessive_penetration(u)
          : std::string();
  if (may_cut && (!finite || !result.converged || status_loop_->chattered() || unresolved_impact ||
                  !penetration.empty())) {
    // Automatic time stepping (APDL_MODELING §9.3 item 2): the step is cut instead; the
    // elements return to their committed states, the integrator was not advanced.
    const std::string chatter = status_loop_->chatter_report();
    if (!finite)
      cut_reason_ = "the solution is not a finite number";
    else if (!result.converged)
      cut_reason_ = fmt::format(
          "no convergence in {} iterations (force residual {:.3e} > {:g} x reference {:.3e}){}",
          conv.max_iterations, result.residual_norm, conv.force_tolerance, result.reference,
          chatter.empty() ? "" : "; status changes:" + chatter);
    else if (status_loop_->chattered())
      cut_reason_ = "contact status chatter (open/closed changes in the iterations):" + chatter;
    else if (unresolved_impact)
      cut_reason_ = fmt::format(
          "{} status change(s) in a step longer than {:.4g} (T/30 of the contact frequency)",
          inc.n_status_changes, impact_step_limit_);
    else
      cut_reason_ = penetration;
    status_loop_->revert();
    factor_valid_ = false;
    return false;
  }
  if (!finite) fail_not_finite(u, label);
  if (!result.converged) {
    const std::string chatter = status_loop_->chatter_report();
    const std::string message = fmt::format(
        "load step {} substep {} (t = {:g}) did not converge in {} iterations: force residual "
        "{:.4e} > {:g} x reference {:.4e}; {}; use a smaller time step (DELTIM / DTIME) or more "
        "substeps (NSUBST / ITER), allow more iterations (NEQIT), or accept such steps with "
        "--continue-on-nonconvergence",
        label.load_step, label.substep, label.time, conv.max_iterations, result.residual_norm,
        conv.force_tolerance, result.reference,
        chatter.empty() ? largest_residual(u)
                        : "elements that kept changing status (open/closed chatter):" + chatter);
    if (!settings_.continue_on_nonconvergence) throw SolutionError(message);
    Log::warn("{} (accepted: --continue-on-nonconvergence)", message);
  }

  // Accept the step: commit element states, advance the integrator, energy bookkeeping.
  status_loop_->commit(u);
  energy_->add_step(*assembler_, u_, u,
                    {f_ext_old_, inc.f_ext, f_int_old_, inc.f_int, f_damp_old_, inc.f_damp});
  if (dynamic) {
    integrator_->advance(u);
    u_ = integrator_->u();
    v_ = integrator_->v();
    a_ = integrator_->a();
    reactions_ = inc.f_int + inc.f_damp + inertia_of(a_) - inc.f_ext;
  } else {
    u_ = u;
    v_.setZero();
    a_.setZero();
    reactions_ = inc.f_int - inc.f_ext;
  }
  f_ext_old_ = inc.f_ext;
  f_int_old_ = inc.f_int;
  f_damp_old_ = inc.f_damp;
  acel_ = frame_acceleration(at);
  time_ = label.time;
  refresh_connectivity();
  return true;
}

const VectorXd& DirectSolution::inertia_of(const VectorXd& a) {
  if (a.size() != inertia_a_.size() || a != inertia_a_) {
    inertia_a_ = a;
    assembler_->inertia_force(a, inertia_);
  }
  return inertia_;
}

std::string DirectSolution::elements_at(int index) const {
  std::string list;
  int shown = 0;
  for (std::size_t e = 0; e < structure_.elements().size(); ++e) {
    const auto& idx = dofs_->element_indices(e);
    if (std::find(idx.begin(), idx.end(), index) == idx.end()) continue;
    if (shown++ < 8)
      list += fmt::format("{}{}", shown > 1 ? ", " : "", structure_.elements()[e]->id());
  }
  if (shown > 8) list += ", ...";
  return shown == 0 ? std::string("no element") : (shown == 1 ? "element " : "elements ") + list;
}

std::string DirectSolution::largest_residual(const VectorXd& u) {
  VectorXd r;
  double reference = 0.0;
  residual(u, r, reference);
  const int nf = dofs_->n_free();
  if (nf == 0) return "no free DOF";
  Eigen::Index worst = 0;
  r.head(nf).cwiseAbs().maxCoeff(&worst);
  const int i = static_cast<int>(worst);
  return fmt::format("the largest out-of-balance force {:.4e} is at {} ({})", r(i),
                     structure_.describe_dof(*dofs_, i), elements_at(i));
}

void DirectSolution::fail_not_finite(const VectorXd& u, const StepLabel& label) {
  const int nf = dofs_->n_free();
  int bad = -1;
  for (int i = 0; i < nf && bad < 0; ++i)
    if (!std::isfinite(u(i))) bad = i;
  std::string where;
  if (bad >= 0) {
    where =
        fmt::format("{} = {} ({})", structure_.describe_dof(*dofs_, bad), u(bad), elements_at(bad));
  } else {
    VectorXd r;
    double reference = 0.0;
    residual(u, r, reference);
    for (int i = 0; i < nf && bad < 0; ++i)
      if (!std::isfinite(r(i))) bad = i;
    if (bad >= 0) {
      where = fmt::format("the out-of-balance force at {} is {} ({})",
                          structure_.describe_dof(*dofs_, bad), r(bad), elements_at(bad));
    } else if (nf > 0) {  // finite entries whose norm overflows
      Eigen::Index worst = 0;
      r.head(nf).cwiseAbs().maxCoeff(&worst);
      bad = static_cast<int>(worst);
      where = fmt::format("the out-of-balance force {:g} at {} ({}) is too large to measure",
                          r(bad), structure_.describe_dof(*dofs_, bad), elements_at(bad));
    }
  }
  throw SolutionError(fmt::format(
      "load step {} substep {} (t = {:g}): the solution is not a finite number: {}; the "
      "results of the steps before it are kept. Check for huge loads or stiffnesses, a "
      "near-mechanism, or a time step too large for the model",
      label.load_step, label.substep, label.time, where));
}

void DirectSolution::store(double time, int load_step, int substep, bool dynamic,
                           const OutputSelection& selection) {
  TimePoint point;
  point.time = time;
  point.load_step = load_step;
  point.substep = substep;
  // Quantities OUTRES does not write at this point are not computed (absent, NaN in the file).
  const auto wanted = [&](OutputItem i) { return !selection[i].none(); };
  if (wanted(OutputItem::NSOL)) point.displacement = structure_.nodal_table(*dofs_, u_);
  if (dynamic || structure_.options().type == AnalysisType::Transient) {
    if (wanted(OutputItem::VSOL)) point.velocity = structure_.nodal_table(*dofs_, v_);
    if (wanted(OutputItem::ASOL)) point.acceleration = structure_.nodal_table(*dofs_, a_);
  }
  if (wanted(OutputItem::RSOL)) point.reaction = structure_.reaction_table(*dofs_, reactions_);
  if (selection.any_element_item())
    point.element_results = structure_.element_results(*assembler_, u_, v_);
  apply_output_selection(selection, writer_.node_ids(), point);
  point.energy = energy_->columns(kinetic_energy());
  point.frame_acceleration = acel_;
  writer_.append(std::move(point));
  ++stats_.n_stored;
}

}  // namespace impactfe
