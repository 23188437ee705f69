#include "analysis/equilibrium_increment.h"

#include <fmt/format.h>

#include <algorithm>
#include <cmath>
#include <utility>

#include "core/log.h"
#include "linalg/mass_solve.h"

namespace impactfe {

EquilibriumIncrement::EquilibriumIncrement(const Structure& structure, const RunSettings& settings,
                                           AnalysisStatistics& stats, MotionState& state,
                                           const StepLoads& loads, EnergyBalance& energy)
    : structure_(structure),
      settings_(settings),
      stats_(stats),
      state_(state),
      loads_(loads),
      energy_(energy) {}

void EquilibriumIncrement::bind(Discretisation& disc, TimeIntegrator* integrator) {
  disc_ = &disc;
  integrator_ = integrator;
  inertia_a_ = VectorXd();  // a cached M a belongs to the old numbering
  if (disc.condensation_note()) condensation_note_ = *disc.condensation_note();
}

void EquilibriumIncrement::start_motion(const LoadPoint& at, double h) {
  Assembler& assembler = disc_->assembler();
  const int nf = disc_->dofs().n_free();
  // The initial accelerations follow from the element states the initial conditions produce
  // (as MAPDL): a slider stretched past FSLIDE by IC starts slipping (spring force FSLIDE, not
  // K1 times the stretch), a gap the IC open starts open.
  disc_->status_loop().settle(state_.u);
  VectorXd f_int, f_damp, f0;
  assembler.assemble({}, state_.u, state_.v, Assembler::Output{nullptr, &f_int, &f_damp});
  loads_.external_force(*disc_, at, state_.u, f0);
  const VectorXd rhs = f0 - f_int - f_damp;
  std::vector<int> massive;
  const VectorXd mass_diagonal = assembler.mass_diagonal();
  for (int i = 0; i < nf; ++i)
    if (mass_diagonal(i) > 0.0) massive.push_back(i);
  state_.a.setZero();
  if (!massive.empty()) {
    const int nm = static_cast<int>(massive.size());
    std::vector<int> position(static_cast<std::size_t>(nf), -1);
    for (int k = 0; k < nm; ++k) position[static_cast<std::size_t>(massive[k])] = k;
    const SparseMatrix mm = assembler.mass_block_lower(position, nm);
    VectorXd r(nm);
    for (int k = 0; k < nm; ++k) r(k) = rhs(massive[k]);
    const VectorXd am = solve_mass_system(mm, r).a;
    for (int k = 0; k < nm; ++k) state_.a(massive[k]) = am(k);
  }
  integrator_->start(state_.u, state_.v, state_.a, h);
  state_.f_ext_old = f0;
  state_.f_int_old = f_int;
  state_.f_damp_old = f_damp;
  disc_->invalidate_factor();
}

void EquilibriumIncrement::prepare(const LoadPoint& at, const StepLabel& label, bool dynamic,
                                   VectorXd& u) {
  Increment& inc = inc_;
  inc.dynamic = dynamic;
  inc.label = label;
  inc.n_status_changes = 0;
  loads_.external_force(*disc_, at, state_.u, inc.f_ext);  // into the kept vector
  inc.at = at;
  inc.follower = structure_.context().large_deflection && !at.current->pressures.empty();
  if (inc.follower)
    inc.f_pressure =
        pressure_forces(structure_.elements(), disc_->dofs(), structure_.context(), at, state_.u);
  inc.v = state_.v;
  inc.a = state_.a;
  if (dynamic) {
    integrator_->predict(u);
  } else {
    u = state_.u;
    if (static_delta_.size() == u.size()) u += static_delta_;
  }
  static_delta_.resize(0);
  loads_.prescribe(*disc_, at, u);
  inc.coeff = dynamic ? integrator_->coefficients() : IntegrationCoefficients{1.0, 0.0, 0.0};
  inc.weights = dynamic ? integrator_->weights() : ResidualWeights{};
  if (!disc_->factor_valid_for(inc.coeff)) disc_->invalidate_factor();
  // Terms of the residual fixed within the step: old-state forces and inertia (generalized-α).
  if (dynamic) {
    const ResidualWeights& w = inc.weights;
    inc.fixed_terms = w.external * inc.f_ext + (1.0 - w.external) * state_.f_ext_old -
                      (1.0 - w.inertia) * inertia_of(integrator_->a()) -
                      (1.0 - w.stiffness) * (state_.f_int_old + state_.f_damp_old);
  }
}

NewtonOptions EquilibriumIncrement::newton_options(const LoadPoint& at) const {
  // The tangent varies with u under large deflection, stress stiffening or plasticity: full
  // Newton re-forms it every `reformulation` iterations (KRF / NROPT); otherwise only a status
  // change does.
  const ConvergenceOptions& conv = structure_.options().convergence;
  const ElementContext& ctx = structure_.context();
  NewtonOptions newton;
  newton.max_iterations = conv.max_iterations;
  newton.full_newton = conv.full_newton;
  newton.line_search = conv.line_search;
  newton.line_search_auto = conv.line_search_auto;
  newton.reform_every = at.current->reformulation;
  newton.tangent_varies =
      disc_->assembler().is_nonlinear() &&
      (ctx.large_deflection || ctx.stress_stiffening || disc_->status_loop().has_history());
  return newton;
}

SubstepOutcome EquilibriumIncrement::find_equilibrium(const LoadPoint& at, const StepLabel& label,
                                                      bool dynamic, bool may_cut) {
  const ConvergenceOptions& conv = structure_.options().convergence;
  VectorXd& u = step_state_;  // kept: a step allocates no vector of model size
  prepare(at, label, dynamic, u);
  const NewtonOptions newton = newton_options(at);
  StatusLoop& status_loop = disc_->status_loop();
  status_loop.begin_step();
  NewtonResult result;
  SubstepOutcome outcome;
  try {
    // Follower pressures load the linear part's DOFs through u, which the condensed system
    // does not see: such steps take full Newton.
    const bool condensed = dynamic && disc_->condensation() != nullptr && !inc_.follower &&
                           solve_condensed(u, newton, result);
    if (!condensed) {
      // Full Newton on all free DOFs (also the fallback when a condensed step left a residual
      // the full criterion does not accept; it starts from the condensed iterate).
      const int before = result.iterations;
      result = NewtonRaphson(newton, ConvergenceTest(conv)).solve(*this, u);
      result.iterations += before;
    }
  } catch (const SolutionError& e) {  // e.g. a plastic mechanism: a smaller step may pass
    status_loop.end_step();
    if (!may_cut) throw;
    outcome.failure = e.what();
    return outcome;
  }
  status_loop.end_step();
  stats_.n_iterations += result.iterations;
  stats_.line_search = stats_.line_search || newton.line_search || newton.line_search_auto;
  stats_.n_line_searches += result.line_searches;
  stats_.n_status_changes += inc_.n_status_changes;
  outcome.status_changes = inc_.n_status_changes;
  outcome.step = dynamic ? integrator_->step() : 0.0;

  const bool finite = result.finite && u.head(disc_->dofs().n_free()).allFinite();
  if (may_cut) {
    // Automatic time stepping (APDL_MODELING §9.3 item 2): the schedule cuts the step instead;
    // KEYOPT(7) = 1 contact: penetration > FTOLN·depth cuts too.
    outcome.failure = failure(result, finite);
    if (outcome.failure.empty()) outcome.penetration = disc_->excessive_penetration(state_.u, u);
    return outcome;
  }
  if (!finite) fail_not_finite(u, label);
  if (!result.converged) report_no_convergence(result, u, label);
  return outcome;
}

std::string EquilibriumIncrement::failure(const NewtonResult& result, bool finite) const {
  const ConvergenceOptions& conv = structure_.options().convergence;
  const StatusLoop& status_loop = disc_->status_loop();
  const std::string chatter = status_loop.chatter_report();
  if (!finite) return "the solution is not a finite number";
  if (!result.converged)
    return fmt::format(
        "no convergence in {} iterations (force residual {:.3e} > {:g} x reference {:.3e}){}",
        conv.max_iterations, result.residual_norm, conv.force_tolerance, result.reference,
        chatter.empty() ? "" : "; status changes:" + chatter);
  if (status_loop.chattered())
    return "contact status chatter (open/closed changes in the iterations):" + chatter;
  return {};
}

void EquilibriumIncrement::report_no_convergence(const NewtonResult& result, const VectorXd& u,
                                                 const StepLabel& label) {
  const ConvergenceOptions& conv = structure_.options().convergence;
  const std::string chatter = disc_->status_loop().chatter_report();
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

void EquilibriumIncrement::accept() {
  const VectorXd& u = step_state_;
  const Increment& inc = inc_;
  disc_->status_loop().commit(u);
  energy_.add_step(
      disc_->assembler(), state_.u, u,
      {state_.f_ext_old, inc.f_ext, state_.f_int_old, inc.f_int, state_.f_damp_old, inc.f_damp});
  const VectorXd u_old = state_.u;
  const VectorXd reactions_old = state_.reactions;
  if (inc.dynamic) {
    integrator_->advance(u);
    state_.u = integrator_->u();
    state_.v = integrator_->v();
    state_.a = integrator_->a();
    state_.reactions = inc.f_int + inc.f_damp + inertia_of(state_.a) - inc.f_ext;
  } else {
    state_.u = u;
    state_.v.setZero();
    state_.a.setZero();
    state_.reactions = inc.f_int - inc.f_ext;
  }
  // Prescribed motion puts energy in through the reactions at the constrained DOFs (the tail of
  // the active numbering): ½ (R_n + R_{n+1})·Δu_c, the trapezoidal rule as for the loads.
  const Eigen::Index nc = disc_->dofs().n_constrained();
  if (nc > 0 && reactions_old.size() == state_.reactions.size())
    energy_.add_support_work(0.5 * (reactions_old.tail(nc) + state_.reactions.tail(nc))
                                       .dot(state_.u.tail(nc) - u_old.tail(nc)));
  state_.f_ext_old = inc.f_ext;
  state_.f_int_old = inc.f_int;
  state_.f_damp_old = inc.f_damp;
  state_.acel = frame_acceleration(inc.at);
  state_.time = inc.label.time;
}

void EquilibriumIncrement::reject() {
  // The elements return to their committed states; the integrator was not advanced.
  disc_->status_loop().revert();
  disc_->invalidate_factor();
}

const VectorXd& EquilibriumIncrement::inertia_of(const VectorXd& a) {
  if (a.size() != inertia_a_.size() || a != inertia_a_) {
    inertia_a_ = a;
    disc_->assembler().inertia_force(a, inertia_);
  }
  return inertia_;
}

// ---- the equations of the increment -----------------------------------------------------------

double EquilibriumIncrement::residual(const VectorXd& u, VectorXd& r, double& reference) {
  Increment& inc = inc_;
  const int nf = disc_->dofs().n_free();
  Assembler& assembler = disc_->assembler();
  const bool tangent_follows = std::exchange(tangent_expected_, false);
  if (inc.dynamic) integrator_->kinematics(u, inc.v, inc.a);
  if (inc.follower) {
    // Follower pressure (large deflection): the load of the deformed faces at this iterate. Its
    // load stiffness is left out of the tangent (it is unsymmetric and the solvers are
    // symmetric), so Newton converges linearly on this part.
    const VectorXd fp =
        pressure_forces(structure_.elements(), disc_->dofs(), structure_.context(), inc.at, u);
    const VectorXd delta = fp - inc.f_pressure;
    inc.f_pressure = fp;
    inc.f_ext += delta;
    if (inc.dynamic) inc.fixed_terms += inc.weights.external * delta;
  }
  if (inc.dynamic) {
    assembler.assemble(
        inc.coeff, u, inc.v,
        Assembler::Output{nullptr, &inc.f_int, &inc.f_damp, &inc.inertia, tangent_follows}, &inc.a);
    inertia_a_ = inc.a;
    inertia_ = inc.inertia;
    r = inc.fixed_terms - inc.weights.inertia * inc.inertia -
        inc.weights.stiffness * (inc.f_int + inc.f_damp);
    reference = std::max(
        {inc.f_ext.head(nf).norm(), inc.inertia.head(nf).norm(), inc.f_int.head(nf).norm()});
  } else {
    assembler.assemble(
        inc.coeff, u, inc.v,
        Assembler::Output{nullptr, &inc.f_int, &inc.f_damp, nullptr, tangent_follows});
    r = inc.f_ext - inc.f_int;
    reference = std::max(inc.f_ext.head(nf).norm(), inc.f_int.head(nf).norm());
  }
  return r.head(nf).norm();
}

bool EquilibriumIncrement::update_status(const VectorXd& u) {
  const int changed = disc_->status_loop().update(u, inc_.label);
  if (changed == 0) return false;
  inc_.n_status_changes += changed;
  disc_->invalidate_factor();
  return true;
}

// ---- factorization and its failures -----------------------------------------------------------

void EquilibriumIncrement::factorize(const IntegrationCoefficients& coeff, const VectorXd& u) {
  try {
    disc_->factorize(coeff, u, state_.v);
  } catch (const SingularMatrixError& e) {
    fail_singular(coeff, e.column());
  }
  warn_negative_pivots(coeff);
}

void EquilibriumIncrement::fail_singular(const IntegrationCoefficients& coeff, int column) {
  const std::string dof = disc_->describe_dof(column);
  const StepLabel& label = inc_.label;
  // With plasticity a tangent that was regular before (the count includes this attempt) can
  // lose its stiffness: perfectly plastic (Et = 0) parts forming a mechanism, i.e. a load
  // above the collapse load.
  if (disc_->status_loop().has_history() && disc_->solver().counters().factorizations > 1)
    throw SolutionError(fmt::format(
        "load step {} substep {} (t = {:g}): the tangent stiffness became singular at {} "
        "({}): the plastic elements form a mechanism (the load exceeds the collapse load, or "
        "perfectly plastic parts (Et = 0) yield together in one iteration); use smaller load "
        "increments (NSUBST) or a hardening tangent modulus",
        label.load_step, label.substep, label.time, dof, disc_->elements_at(column)));
  if (coeff.cM != 0.0)
    throw ModelError(fmt::format(
        "the effective matrix K + cC C + cM M of the time step is singular at {} (zero pivot, "
        "{}): it has neither stiffness nor mass there; constrain it with D, connect it to the "
        "structure or give it mass",
        dof, disc_->elements_at(column)));
  throw ModelError(
      fmt::format("the model is singular: {} is unrestrained (zero pivot in the stiffness "
                  "matrix, {}); constrain it with D or connect it to the structure",
                  dof, disc_->elements_at(column)));
}

void EquilibriumIncrement::warn_negative_pivots(const IntegrationCoefficients& coeff) {
  // A negative pivot of a dynamic effective matrix: the tangent stiffness is negative there
  // (compressive stress stiffening, buckling) by more than the inertia term cM M holds, so the
  // step may leave the stable path.
  const LinearSolver& solver = disc_->solver();
  if (coeff.cM == 0.0 || solver.negative_pivots() <= 0 || negative_pivot_warned_) return;
  negative_pivot_warned_ = true;
  const int row = solver.first_negative_pivot_row();
  Log::warn(
      "load step {} substep {} (t = {:g}): the effective matrix K + cC C + cM M has {} negative "
      "pivot(s), the first at {} ({}): the tangent stiffness there is negative (compression, "
      "buckling) beyond what the inertia of the time step holds; the solution may follow an "
      "unstable path. Use a smaller time step (DELTIM / DTIME)",
      inc_.label.load_step, inc_.label.substep, inc_.label.time, solver.negative_pivots(),
      row >= 0 ? disc_->describe_dof(row) : "?", row >= 0 ? disc_->elements_at(row) : "?");
}

std::string EquilibriumIncrement::largest_residual(const VectorXd& u) {
  VectorXd r;
  double reference = 0.0;
  residual(u, r, reference);
  const int nf = disc_->dofs().n_free();
  if (nf == 0) return "no free DOF";
  Eigen::Index worst = 0;
  r.head(nf).cwiseAbs().maxCoeff(&worst);
  const int i = static_cast<int>(worst);
  return fmt::format("the largest out-of-balance force {:.4e} is at {} ({})", r(i),
                     disc_->describe_dof(i), disc_->elements_at(i));
}

void EquilibriumIncrement::fail_not_finite(const VectorXd& u, const StepLabel& label) {
  const int nf = disc_->dofs().n_free();
  int bad = -1;
  for (int i = 0; i < nf && bad < 0; ++i)
    if (!std::isfinite(u(i))) bad = i;
  std::string where;
  if (bad >= 0) {
    where = fmt::format("{} = {} ({})", disc_->describe_dof(bad), u(bad), disc_->elements_at(bad));
  } else {
    VectorXd r;
    double reference = 0.0;
    residual(u, r, reference);
    for (int i = 0; i < nf && bad < 0; ++i)
      if (!std::isfinite(r(i))) bad = i;
    if (bad >= 0) {
      where = fmt::format("the out-of-balance force at {} is {} ({})", disc_->describe_dof(bad),
                          r(bad), disc_->elements_at(bad));
    } else if (nf > 0) {  // finite entries whose norm overflows
      Eigen::Index worst = 0;
      r.head(nf).cwiseAbs().maxCoeff(&worst);
      bad = static_cast<int>(worst);
      where = fmt::format("the out-of-balance force {:g} at {} ({}) is too large to measure",
                          r(bad), disc_->describe_dof(bad), disc_->elements_at(bad));
    }
  }
  throw SolutionError(fmt::format(
      "load step {} substep {} (t = {:g}): the solution is not a finite number: {}; the "
      "results of the steps before it are kept. Check for huge loads or stiffnesses, a "
      "near-mechanism, or a time step too large for the model",
      label.load_step, label.substep, label.time, where));
}

std::string EquilibriumIncrement::condensation_summary() const {
  if (condensation_note_.empty() || condensed_steps_ + full_fallback_steps_ == 0)
    return condensation_note_;
  return fmt::format("{}; {} steps condensed, {} finished by full Newton{}", condensation_note_,
                     condensed_steps_, full_fallback_steps_, condensed_tangent_note());
}

std::string EquilibriumIncrement::condensed_tangent_note() const {
  if (disc_ == nullptr || disc_->condensation() == nullptr) return "";
  const UpdatableDenseFactor& f = disc_->condensation()->tangent_factor();
  if (f.full_factorizations() == 0) return "";
  return fmt::format("; the condensed tangent: {} factorization(s), {} rank-one update(s)",
                     f.full_factorizations(), f.rank_one_updates());
}

}  // namespace impactfe
