#include "analysis/direct_solution.h"

#include <Eigen/SparseCholesky>
#include <cmath>
#include <functional>
#include <map>

#include "core/log.h"

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

constexpr int kChatterLimit = 4;  // status flips of one element in one step (spec §10.3)

}  // namespace

DirectSolution::DirectSolution(Structure& structure, ResultsWriter& writer,
                               const RunSettings& settings, AnalysisStatistics& stats)
    : structure_(structure),
      writer_(writer),
      settings_(settings),
      stats_(stats),
      ctx_(structure.context()) {
  for (const auto& e : structure_.elements()) is_gap_.push_back(e->has_status());
}

DirectSolution::StepTiming DirectSolution::timing(const LoadStep& step, double t_start,
                                                  bool transient) const {
  StepTiming t;
  t.t_start = t_start;
  if (step.time_end) {
    t.t_end = *step.time_end;
  } else if (transient) {
    throw InputError(step.where, fmt::format("load step {}: TIME (end time) is required in a "
                                             "transient analysis",
                                             step.number));
  } else {
    t.t_end = static_cast<double>(step.number);  // static default: the load-step number
  }
  if (!(t.t_end > t_start))
    throw InputError(step.where,
                     fmt::format("load step {}: end time {} does not increase (previous end {})",
                                 step.number, t.t_end, t_start));
  const double span = t.t_end - t_start;
  if (step.dt) {
    if (!(*step.dt > 0.0))
      throw InputError(
          step.where, fmt::format("load step {}: time step {} must be > 0", step.number, *step.dt));
    t.n_substeps = std::max(1, static_cast<int>(std::lround(span / *step.dt)));
  } else if (step.n_substeps) {
    if (*step.n_substeps <= 0)
      throw InputError(step.where, fmt::format("load step {}: number of substeps {} must be > 0",
                                               step.number, *step.n_substeps));
    t.n_substeps = *step.n_substeps;
  }
  t.h = span / t.n_substeps;
  return t;
}

void DirectSolution::set_constraints(const LoadStep& step) {
  std::set<DofKey> wanted = structure_.constraints_of(step);
  if (dofs_ && wanted == constrained_) return;
  auto dofs = std::make_unique<DofMap>(structure_.elements(), wanted);
  if (dofs_) {
    u_ = remap(u_, *dofs_, *dofs);
    v_ = remap(v_, *dofs_, *dofs);
    a_ = remap(a_, *dofs_, *dofs);
    f_ext_old_ = remap(f_ext_old_, *dofs_, *dofs);
    f_int_old_ = remap(f_int_old_, *dofs_, *dofs);
    f_damp_old_ = remap(f_damp_old_, *dofs_, *dofs);
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
  mass_all_ = assembler_->mass_matrix();
  frame_load_ = FrameAccelerationLoad(structure_.elements(), *dofs_, ctx_);
  if (solver_) retired_ += solver_->counters();  // keep the previous numbering's work
  solver_ = make_linear_solver(dofs_->n_free());
  effective_ = assembler_->pattern();
  factor_valid_ = false;
  stats_.n_dofs = dofs_->n_free();
}

VectorXd DirectSolution::external_force(const LoadPoint& at) const {
  return nodal_forces(*dofs_, at) + frame_load_(frame_acceleration(at));
}

void DirectSolution::factorize(const IntegrationCoefficients& coeff, const VectorXd& u) {
  assembler_->assemble(coeff, u, v_, Assembler::Output{&effective_, nullptr, nullptr});
  try {
    if (!factor_valid_ && solver_->counters().analyses == 0) solver_->analyze_pattern(effective_);
    solver_->factorize(effective_);
  } catch (const SingularMatrixError& e) {
    throw ModelError(
        fmt::format("the model is singular: {} is unrestrained (zero pivot in the {} matrix); "
                    "constrain it with D or connect it to the structure",
                    structure_.describe_dof(*dofs_, e.column()),
                    coeff.cM != 0.0 ? "effective stiffness" : "stiffness"));
  }
  factor_valid_ = true;
  factored_ = coeff;
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
  for (int i = 0; i < nf; ++i)
    if (mass_all_.coeff(i, i) > 0.0) massive.push_back(i);
  a_.setZero();
  if (!massive.empty()) {
    const int nm = static_cast<int>(massive.size());
    std::vector<int> position(static_cast<std::size_t>(nf), -1);
    for (int k = 0; k < nm; ++k) position[static_cast<std::size_t>(massive[k])] = k;
    std::vector<Eigen::Triplet<double, int>> triplets;
    for (int col = 0; col < nf; ++col) {
      if (position[static_cast<std::size_t>(col)] < 0) continue;
      for (SparseMatrix::InnerIterator it(mass_all_, col); it; ++it)
        if (it.row() < nf && position[static_cast<std::size_t>(it.row())] >= 0)
          triplets.emplace_back(position[static_cast<std::size_t>(it.row())],
                                position[static_cast<std::size_t>(col)], it.value());
    }
    SparseMatrix mm(nm, nm);
    mm.setFromTriplets(triplets.begin(), triplets.end());
    VectorXd r(nm);
    for (int k = 0; k < nm; ++k) r(k) = rhs(massive[k]);
    Eigen::SimplicialLDLT<SparseMatrix> ldlt(mm);
    const VectorXd am = ldlt.solve(r);
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
  const AnalysisOptions& options = structure_.options();
  if (transient) integrator_ = make_time_integrator(options);
  const LoadStep* previous = nullptr;
  double t_start = 0.0;
  bool first = true;
  for (const LoadStep& step : steps) {
    const StepTiming t = timing(step, t_start, transient);
    set_constraints(step);
    const bool dynamic = transient && step.time_integration;
    if (first) {
      // Store the initial state (t = 0) of a transient, so histories start at rest.
      if (transient) {
        LoadPoint at0{&step, previous, 0.0};
        u_.tail(dofs_->n_constrained()) =
            prescribed_displacements(*dofs_, at0).tail(dofs_->n_constrained());
        if (dynamic) start_dynamics(at0, t.h);
        reactions_ = VectorXd::Zero(dofs_->n_active());
        store(t_start, 0, 0, dynamic);
      }
      first = false;
    }
    if (dynamic) {
      if (!dynamics_started_) {
        start_dynamics(LoadPoint{&step, previous, 0.0}, t.h);
      } else if (std::abs(integrator_->step() - t.h) > 1e-12 * t.h) {
        integrator_->set_step(t.h);  // Houbolt re-samples its history (spec §10.2)
        factor_valid_ = false;
      }
      time_step_advice(t.h);
    } else {
      dynamics_started_ = false;
    }
    for (int k = 1; k <= t.n_substeps; ++k) {
      const double time = t.t_start + k * t.h;
      const LoadPoint at{&step, previous, static_cast<double>(k) / t.n_substeps};
      solve_increment(at, time, step.number, k, dynamic);
      ++stats_.n_substeps;
      const bool last = k == t.n_substeps;
      const int every = step.output.every;
      if (last || (every > 0 && k % every == 0)) store(time, step.number, k, dynamic);
    }
    ++stats_.n_load_steps;
    previous = &step;
    t_start = t.t_end;
  }
  if (transient) {
    // Energy balance at the end (spec: kinetic, strain, gap work, dissipation vs external work);
    // the remainder is the integrator's numerical dissipation (Houbolt damps high modes).
    const double kinetic = 0.5 * v_.dot(mass_all_ * v_);
    const double strain = internal_work_ - gap_work_;
    const double balance = external_work_ - kinetic - strain - gap_work_ - damping_work_;
    stats_.notes.push_back(fmt::format(
        "energy at t = {:.6g}: kinetic {:.6g}, strain {:.6g}, gap work {:.6g}, damping {:.6g}, "
        "external work {:.6g}, numerical dissipation {:.6g}",
        time_, kinetic, strain, gap_work_, damping_work_, external_work_, balance));
  }
  SolverCounters total = retired_;
  if (solver_) total += solver_->counters();
  record_solver_counters(stats_, total);
}

void DirectSolution::solve_increment(const LoadPoint& at, double time, int load_step, int substep,
                                     bool dynamic) {
  const AnalysisOptions& options = structure_.options();
  const ConvergenceOptions& conv = options.convergence;
  const int nf = dofs_->n_free();
  const int nc = dofs_->n_constrained();
  const auto& elements = structure_.elements();

  const VectorXd f_new = external_force(at);
  VectorXd u = dynamic ? integrator_->predict() : u_;
  u.tail(nc) = prescribed_displacements(*dofs_, at).tail(nc);

  const IntegrationCoefficients coeff =
      dynamic ? integrator_->coefficients() : IntegrationCoefficients{1.0, 0.0, 0.0};
  const ResidualWeights w = dynamic ? integrator_->weights() : ResidualWeights{};
  if (factor_valid_ &&
      (coeff.cK != factored_.cK || coeff.cC != factored_.cC || coeff.cM != factored_.cM))
    factor_valid_ = false;
  // Tangent varies with u under large deflection or stress stiffening: full Newton re-forms it
  // every `reformulation` iterations (KRF / NROPT); otherwise only a status change re-forms it.
  const bool tangent_varies =
      assembler_->is_nonlinear() && (ctx_.large_deflection || ctx_.stress_stiffening);
  const int reform_every = std::max(1, at.current->reformulation);

  std::map<int, int> flips;  // element index -> status changes in this step
  bool status_changed = false;
  VectorXd v = v_, a = a_, f_int, f_damp, r;
  double residual_norm = 0.0, reference = 0.0;
  bool converged = false;
  int iteration = 0;
  VectorXd ue, inertia_new;
  // Terms of the residual fixed within the step: old-state forces and inertia (generalized-α).
  VectorXd fixed_terms;
  if (dynamic)
    fixed_terms = w.external * f_new + (1.0 - w.external) * f_ext_old_ -
                  (1.0 - w.inertia) * (mass_all_ * integrator_->a()) -
                  (1.0 - w.stiffness) * (f_int_old_ + f_damp_old_);
  for (; iteration <= conv.max_iterations; ++iteration) {
    if (dynamic) integrator_->kinematics(u, v, a);
    assembler_->assemble(coeff, u, v, Assembler::Output{nullptr, &f_int, &f_damp});
    if (dynamic) {
      inertia_new = mass_all_ * a;
      r = fixed_terms - w.inertia * inertia_new - w.stiffness * (f_int + f_damp);
      reference = std::max({f_new.head(nf).norm(), inertia_new.head(nf).norm(),
                            f_int.head(nf).norm(), conv.force_minref});
    } else {
      r = f_new - f_int;
      reference = std::max({f_new.head(nf).norm(), f_int.head(nf).norm(), conv.force_minref});
    }
    residual_norm = r.head(nf).norm();
    if (!status_changed && residual_norm <= conv.force_tolerance * reference &&
        (iteration > 0 || residual_norm == 0.0 || nf == 0)) {
      converged = true;
      break;
    }
    if (iteration == conv.max_iterations) break;
    if (nf == 0) {
      converged = true;
      break;
    }
    const bool reform = !factor_valid_ || status_changed ||
                        (tangent_varies && conv.full_newton && iteration % reform_every == 0);
    if (reform) factorize(coeff, u);
    const VectorXd du = solver_->solve(VectorXd(r.head(nf)));
    u.head(nf) += du;
    if (conv.displacement_tolerance &&
        du.norm() > *conv.displacement_tolerance * std::max(u.head(nf).norm(), 1e-30)) {
      status_changed = true;  // displacement criterion not met: force another iteration
    } else {
      status_changed = false;
    }
    // Status loop: gaps open/close, sliders stick/slide, judged on the new iterate.
    for (std::size_t e = 0; e < elements.size(); ++e) {
      if (!is_gap_[e]) continue;
      assembler_->gather(e, u, ue);
      if (elements[e]->update_status(ctx_, ue)) {
        status_changed = true;
        factor_valid_ = false;
        ++stats_.n_status_changes;
        if (++flips[static_cast<int>(e)] == kChatterLimit) {
          elements[e]->freeze_status(true);
          Log::warn(
              "load step {} substep {} (t = {:g}): element {} changed status {} times; "
              "status frozen for the rest of the step",
              load_step, substep, time, elements[e]->id(), kChatterLimit);
        }
      }
    }
  }
  stats_.n_iterations += iteration;
  for (const auto& [e, count] : flips)
    if (count >= kChatterLimit) elements[static_cast<std::size_t>(e)]->freeze_status(false);

  if (!converged) {
    std::string chatter;
    for (const auto& [e, count] : flips)
      if (count >= 2)
        chatter += fmt::format(" {}({}x)", elements[static_cast<std::size_t>(e)]->id(), count);
    const std::string message = fmt::format(
        "load step {} substep {} (t = {:g}) did not converge in {} iterations: force residual "
        "{:.4e} > {:g} x reference {:.4e}{}",
        load_step, substep, time, conv.max_iterations, residual_norm, conv.force_tolerance,
        reference, chatter.empty() ? "" : "; elements that kept changing status:" + chatter);
    if (!settings_.continue_on_nonconvergence) throw SolutionError(message);
    Log::warn("{} (accepted: --continue-on-nonconvergence)", message);
  }

  // Accept the step: commit element states, advance the integrator, energy bookkeeping.
  for (std::size_t e = 0; e < elements.size(); ++e) {
    if (!is_gap_[e]) continue;
    assembler_->gather(e, u, ue);
    elements[e]->commit(ue);
  }
  const VectorXd du = u - u_;
  external_work_ += 0.5 * (f_new + f_ext_old_).dot(du);
  damping_work_ += 0.5 * (f_damp + f_damp_old_).dot(du);
  {
    // Internal work split into gap elements and the rest (trapezoidal rule on each).
    VectorXd ue_old, ue_new, f_now;
    Eigen::MatrixXd k;
    if (gap_force_old_.size() != elements.size())
      gap_force_old_.assign(elements.size(), VectorXd());
    for (std::size_t e = 0; e < elements.size(); ++e) {
      if (!is_gap_[e]) continue;
      assembler_->gather(e, u_, ue_old);
      assembler_->gather(e, u, ue_new);
      elements[e]->tangent(ctx_, ue_new, k, f_now);
      VectorXd& f_old = gap_force_old_[e];
      if (f_old.size() != f_now.size()) f_old = VectorXd::Zero(f_now.size());
      gap_work_ += 0.5 * (f_old + f_now).dot(ue_new - ue_old);
      f_old = f_now;
    }
    internal_work_ += 0.5 * (f_int + f_int_old_).dot(du);
  }
  if (dynamic) {
    integrator_->advance(u);
    u_ = integrator_->u();
    v_ = integrator_->v();
    a_ = integrator_->a();
    reactions_ = f_int + f_damp + mass_all_ * a_ - f_new;
  } else {
    u_ = u;
    v_.setZero();
    a_.setZero();
    reactions_ = f_int - f_new;
  }
  f_ext_old_ = f_new;
  f_int_old_ = f_int;
  f_damp_old_ = f_damp;
  time_ = time;
}

void DirectSolution::store(double time, int load_step, int substep, bool dynamic) {
  TimePoint point;
  point.time = time;
  point.load_step = load_step;
  point.substep = substep;
  point.displacement = structure_.nodal_table(*dofs_, u_);
  if (dynamic || structure_.options().type == AnalysisType::Transient) {
    point.velocity = structure_.nodal_table(*dofs_, v_);
    point.acceleration = structure_.nodal_table(*dofs_, a_);
  }
  point.reaction = structure_.reaction_table(*dofs_, reactions_);
  point.element_results = structure_.element_results(*assembler_, u_, v_);
  const double kinetic = 0.5 * v_.dot(mass_all_ * v_);
  point.energy["kinetic"] = kinetic;
  point.energy["strain"] = internal_work_ - gap_work_;
  point.energy["external_work"] = external_work_;
  point.energy["gap_work"] = gap_work_;
  point.energy["dissipation"] = damping_work_;
  writer_.append(point);
  ++stats_.n_stored;
}

void DirectSolution::time_step_advice(double h) {
  // Highest frequency that matters for the impact (thesis §III.C, eq. 5-3-1): each gap closed,
  // acting between the bodies it joins, taken as rigid: w = sqrt(k (1/m_I + 1/m_J)), where m is
  // the mass (in the gap direction) of the body the node belongs to - the nodes connected
  // through non-gap elements - and a constrained node is ground (infinite mass).
  const auto& elements = structure_.elements();
  std::map<int, int> parent;
  std::function<int(int)> find = [&](int n) {
    auto it = parent.find(n);
    if (it == parent.end() || it->second == n) return parent[n] = n;
    return it->second = find(it->second);
  };
  for (std::size_t e = 0; e < elements.size(); ++e) {
    if (is_gap_[e]) continue;
    const auto& keys = elements[e]->dofs();
    for (const auto& k : keys) parent[find(k.node)] = find(keys.front().node);
  }
  // Body mass per direction: row sums of M (exact for lumped, total mass for consistent).
  std::map<std::pair<int, int>, double> body_mass;
  const VectorXd row_sum = mass_all_ * VectorXd::Ones(dofs_->n_active());
  for (int i = 0; i < dofs_->n_active(); ++i) {
    const DofKey& key = dofs_->key(i);
    body_mass[{find(key.node), static_cast<int>(key.dof)}] += row_sum(i);
  }
  double omega_max = 0.0;
  int which = 0;
  for (std::size_t e = 0; e < elements.size(); ++e) {
    const double k = elements[e]->closed_stiffness();
    if (!is_gap_[e] || k <= 0.0) continue;
    double flexibility = 0.0;  // 1/m_I + 1/m_J
    for (int index : dofs_->element_indices(e)) {
      if (index >= dofs_->n_free()) continue;  // ground
      const DofKey& key = dofs_->key(index);
      const double m = body_mass[{find(key.node), static_cast<int>(key.dof)}];
      if (m > 0.0) flexibility += 1.0 / m;
    }
    if (flexibility > 0.0 && std::sqrt(k * flexibility) > omega_max) {
      omega_max = std::sqrt(k * flexibility);
      which = elements[e]->id();
    }
  }
  if (omega_max <= 0.0) return;
  const double period = 2.0 * M_PI / omega_max;
  if (!advice_given_) {
    stats_.notes.push_back(fmt::format(
        "time-step advice: highest contact frequency {:.4g} Hz (element {} closed), T = {:.4g} s, "
        "suggested dt = T/30 = {:.4g} s",
        omega_max / (2.0 * M_PI), which, period, period / 30.0));
    advice_given_ = true;
  }
  if (h > period / 10.0)
    Log::warn(
        "dt = {:.4g} s is coarser than T/10 = {:.4g} s of the contact frequency {:.4g} Hz "
        "(element {} closed); suggested dt = T/30 = {:.4g} s",
        h, period / 10.0, omega_max / (2.0 * M_PI), which, period / 30.0);
}

}  // namespace impactfe
