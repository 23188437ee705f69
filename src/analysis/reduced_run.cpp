#include "analysis/reduced_run.h"

#include <Eigen/Eigenvalues>
#include <chrono>
#include <cmath>
#include <limits>
#include <map>

#include "core/log.h"

namespace impactfe {

VectorXd ReducedRunState::external_force(const ReducedPoint& p) const {
  const std::size_t i = static_cast<std::size_t>(p.step_index);
  const LoadPoint at{&load_steps[i], i > 0 ? &load_steps[i - 1] : nullptr, p.fraction, p.time,
                     &structure->model().time_functions};
  VectorXd f = loads_at(at);
  // LVSCALE: the modal analysis's load vectors, scaled and ramped (KBC) like any load.
  const LoadStep& step = load_steps[i];
  const LoadStep* previous = at.previous;
  const double ramp = step.stepped ? 1.0 : p.fraction;
  if (step.load_vector_scale != 0.0 && ramp > 0.0)
    f += ramp * step.load_vector_scale * modal_load_vector(step.load_vector_step, p.time);
  if (previous && previous->load_vector_scale != 0.0 && ramp < 1.0)
    f += (1.0 - ramp) * previous->load_vector_scale *
         modal_load_vector(previous->load_vector_step, p.time);
  return f;
}

VectorXd ReducedRunState::loads_at(const LoadPoint& at) const {
  // Face pressures of the linear reduced model: on the initial faces.
  return nodal_forces(*dofs, at) + frame_load(frame_acceleration(at)) +
         pressure_forces(structure->elements(), *dofs, structure->context(), at,
                         VectorXd::Zero(dofs->n_active()));
}

VectorXd ReducedRunState::modal_load_vector(int number, double time) const {
  const std::vector<LoadStep>& vectors = structure->model().modal_load_vectors;
  // The deck checks LVSCALE's LDSTEP against the modal analysis when the command is read.
  const LoadStep& modal = vectors.at(static_cast<std::size_t>(number - 1));
  return loads_at(LoadPoint{&modal, nullptr, 1.0, time, &structure->model().time_functions});
}

VectorXd ReducedRunState::expand(const VectorXd& gq, const VectorXd* f) const {
  if (guyan) return guyan->expand(gq, f);
  return modes * gq;
}

VectorXd ReducedRunState::to_active(const VectorXd& free) const {
  VectorXd out = VectorXd::Zero(dofs->n_active());
  out.head(dofs->n_free()) = free.head(dofs->n_free());
  return out;
}

void prepare_reduced_model(ReducedRunState& state, const Structure& structure,
                           const AnalysisRequest& request, const RunSettings& settings,
                           const std::vector<DofKey>& keep, AnalysisStatistics& stats) {
  state.structure = std::make_unique<Structure>(structure.model(), structure.options(), settings);
  state.structure->use_table_nodes(structure.node_ids());
  state.load_steps = request.load_steps;
  state.alpha_damping = structure.options().alpha_damping;
  state.beta_damping = structure.options().beta_damping;
  if (state.load_steps.empty()) throw InputError(request.where, "no load steps were written");
  const LoadStep& first = state.load_steps.front();
  for (const LoadStep& step : state.load_steps) {
    for (const auto& [key, value] : step.constraints)
      if (value != 0.0)
        throw NotImplementedError(
            fmt::format("load step {}: non-zero imposed displacement on {} in a reduced / "
                        "mode-superposition transient is not implemented yet",
                        step.number, describe(key)));
    if (constrained_set(step) != constrained_set(first))
      throw NotImplementedError(fmt::format(
          "load step {}: changing the constrained DOF set in a reduced / mode-superposition "
          "transient is not implemented yet",
          step.number));
  }
  const Structure& s = *state.structure;
  s.refuse_constraint_equations("a reduced, mode-superposition or harmonic analysis");
  if (!s.model().coupled_sets.empty())
    throw NotImplementedError(s.model().coupled_sets.begin()->second.where,
                              "coupled DOF sets (CP) in a reduced / mode-superposition "
                              "transient are not implemented");
  for (const LoadStep& step : state.load_steps)
    if (step.gives_temperatures())
      throw NotImplementedError(step.where,
                                "temperatures (TUNIF, BFUNIF, BF) in a reduced / "
                                "mode-superposition transient are not implemented");
  std::set<DofKey> constrained = s.constraints_of(first);
  {
    const DofMap trial(s.elements(), constrained);
    const Assembler assembler(s.elements(), trial, s.context());
    const SparseMatrix k = assembler.stiffness_matrix(VectorXd::Zero(trial.n_active()));
    const VectorXd diag = k.diagonal();
    const double scale = trial.n_free() ? diag.head(trial.n_free()).cwiseAbs().maxCoeff() : 0.0;
    // Mode superposition keeps a DOF without stiffness that carries mass: it moves in a
    // rigid-body mode (0 Hz), which the modes include (a mass on a gap, GP, alone). So does a
    // full harmonic analysis, where −Ω² M restrains it at any non-zero frequency.
    VectorXd mass_diag;
    if (state.method != "reduced") mass_diag = assembler.mass_matrix().diagonal();
    const std::set<DofKey> kept(keep.begin(), keep.end());
    std::string list;
    int dropped = 0;
    for (int i = 0; i < trial.n_free(); ++i) {
      if (std::abs(diag(i)) > 1e-14 * scale || kept.count(trial.key(i))) continue;
      if (mass_diag.size() > i && mass_diag(i) > 0.0) continue;
      // A load on such a DOF would vanish with it (issue 12: no silent wrong answer).
      for (const LoadStep& step : state.load_steps) {
        const auto f = step.forces.find(trial.key(i));
        if (f == step.forces.end() || f->second == 0.0) continue;
        const auto w = step.force_where.find(trial.key(i));
        throw ModelError(
            w != step.force_where.end() ? w->second : step.where,
            fmt::format("{} carries the force {} = {:g} but has no stiffness, so the "
                        "reduction cannot keep it as a slave; make it a master DOF "
                        "(M) or connect it to the structure",
                        describe(trial.key(i)), force_name(trial.key(i).dof), f->second));
      }
      constrained.insert(trial.key(i));
      if (dropped++ < 20) list += " " + describe(trial.key(i));
    }
    if (dropped) {
      const std::string note = fmt::format(
          "{} DOF(s) without stiffness (not restrained by anything) dropped from the reduction "
          "as constrained slaves:{}{}",
          dropped, list, dropped > 20 ? " ..." : "");
      Log::info("{}", note);
      stats.notes.push_back(note);
    }
  }
  state.dofs = std::make_unique<DofMap>(s.elements(), constrained);
  state.assembler = std::make_unique<Assembler>(s.elements(), *state.dofs, s.context());
  state.mass_all = state.assembler->mass_matrix();
  state.frame_load = FrameAccelerationLoad(s.elements(), *state.dofs, s.context());
  stats.n_dofs = state.dofs->n_free();
  if (state.assembler->is_nonlinear())
    Log::warn(
        "reduced / mode-superposition transient is linear: nonlinear elements keep their initial "
        "stiffness and status (use GP gap conditions for contact)");
}

SparseMatrix damping_matrix(const ReducedRunState& state, const SparseMatrix& k) {
  const int n = state.dofs->n_active();
  SparseMatrix c(n, n);
  if (state.assembler->has_damping()) c = state.assembler->damping_matrix(VectorXd::Zero(n));
  if (state.alpha_damping != 0.0) c += state.alpha_damping * state.mass_all;
  if (state.beta_damping != 0.0) c += state.beta_damping * k;
  return c;
}

std::vector<GeneralizedGap> generalized_gaps(const Model& model, const DofMap& dofs,
                                             const std::function<VectorXd(int)>& row,
                                             const std::string& requirement) {
  std::set<int> active_nodes;
  for (const DofKey& key : dofs.keys()) active_nodes.insert(key.node);
  std::vector<GeneralizedGap> gaps;
  for (const GapCondition& gc : model.gap_conditions) {
    auto end = [&](int node) -> VectorXd {
      if (node == 0 || !active_nodes.count(node)) return {};  // ground
      const DofKey key{node, gc.dof};
      const int i = dofs.index(key);
      if (i < 0)
        throw InputError(gc.where,
                         fmt::format("GP: node {} has no {} DOF", node, dof_name(gc.dof)));
      if (i >= dofs.n_free()) return {};  // constrained: fixed like ground
      VectorXd b = row(i);
      if (b.size() == 0)
        throw InputError(gc.where,
                         fmt::format("GP: {} is not a master DOF; {}", describe(key), requirement));
      return b;
    };
    GeneralizedGap g;
    g.b_i = end(gc.node_i);
    g.b_j = end(gc.node_j);
    g.stiffness = gc.stiffness;
    g.gap = gc.gap;
    g.damping = gc.damping;
    gaps.push_back(std::move(g));
  }
  return gaps;
}

namespace {

/// Static initial state K q = f with a check that K is regular; names the coordinates of the
/// rigid motions otherwise (spec §10.4 step 3).
VectorXd static_initial_state(const MatrixXd& k, const VectorXd& f,
                              const std::function<std::string(int)>& name) {
  Eigen::SelfAdjointEigenSolver<MatrixXd> eig(k);
  const VectorXd& lambda = eig.eigenvalues();
  const double scale = lambda.cwiseAbs().maxCoeff();
  std::string free;
  for (int j = 0; j < lambda.size(); ++j) {
    if (std::abs(lambda(j)) > 1e-10 * scale && scale > 0.0) continue;
    Eigen::Index where = 0;
    eig.eigenvectors().col(j).cwiseAbs().maxCoeff(&where);
    free += " " + name(static_cast<int>(where));
  }
  if (!free.empty())
    throw ModelError(fmt::format(
        "reduced transient: load step 1 carries loads, so its static solution is the initial "
        "state, but the reduced stiffness is singular (free rigid motion of{}); remove the loads "
        "of load step 1 or restrain the structure",
        free));
  return eig.eigenvectors() *
         (lambda.cwiseInverse().asDiagonal() * (eig.eigenvectors().transpose() * f));
}

}  // namespace

void integrate_reduced(ReducedRunState& state, ReducedDynamics& dynamics,
                       const std::function<VectorXd(const VectorXd&)>& reduce,
                       const std::function<VectorXd(const VectorXd&)>& table, const VectorXd& q0,
                       const VectorXd& v0, const std::function<std::string(int)>& coordinate_name,
                       ResultsWriter& writer, AnalysisStatistics& stats, double& seconds_per_step,
                       ProgressObserver* progress) {
  using clock = std::chrono::steady_clock;
  const DofMap& dofs = *state.dofs;
  const int nf = dofs.n_free();
  const Structure& structure = *state.structure;
  const Eigen::MatrixXd nan_table = Eigen::MatrixXd::Constant(
      static_cast<int>(structure.node_ids().size()), 6, std::numeric_limits<double>::quiet_NaN());

  auto store = [&](const ReducedPoint& p) {
    auto nodal = [&](const VectorXd& gq) {
      VectorXd values =
          VectorXd::Constant(dofs.n_active(), std::numeric_limits<double>::quiet_NaN());
      values.head(nf) = table(gq);
      return structure.nodal_table(dofs, values);
    };
    TimePoint tp;
    tp.time = p.time;
    tp.load_step = p.load_step;
    tp.substep = p.substep;
    tp.displacement = nodal(dynamics.q());
    tp.velocity = nodal(dynamics.v());
    tp.acceleration = nodal(dynamics.a());
    tp.reaction = nan_table;
    tp.gap_forces = dynamics.gap_forces();
    tp.energy["kinetic"] = 0.5 * dynamics.v().dot(dynamics.m() * dynamics.v());
    tp.energy["strain"] = 0.5 * dynamics.q().dot(dynamics.k() * dynamics.q());
    writer.append(std::move(tp));
    ++stats.n_stored;
    state.history->append(dynamics.q(), dynamics.v(), dynamics.a(), dynamics.gap_forces());
  };

  const ReducedPoint& p0 = state.points.front();
  const VectorXd f0 = reduce(VectorXd(state.external_force(p0).head(nf)));
  VectorXd f_last = f0;  // the reduced external load of the last point
  VectorXd q_init = q0;
  if (f0.squaredNorm() > 0.0) q_init = static_initial_state(dynamics.k(), f0, coordinate_name);
  dynamics.start(q_init, v0, f0, state.dt > 0.0 ? state.dt : 1.0);
  state.history = std::make_unique<GeneralizedHistory>(
      static_cast<int>(dynamics.q().size()), static_cast<int>(dynamics.gap_forces().size()));
  store(p0);
  ++stats.n_load_steps;

  // End time and substep count of each load step, for the progress line.
  std::map<int, std::pair<double, int>> step_end;
  for (const ReducedPoint& p : state.points) {
    auto& [end, count] = step_end[p.load_step];
    end = std::max(end, p.time);
    count = std::max(count, p.substep);
  }

  double integration = 0.0;
  int n_steps = 0;
  int last_step = p0.load_step;
  for (std::size_t i = 1; i < state.points.size(); ++i) {
    const ReducedPoint& p = state.points[i];
    const auto t0 = clock::now();
    const ReducedPoint& before = state.points[i - 1];
    if (p.step_index != before.step_index &&
        state.load_steps[static_cast<std::size_t>(p.step_index)].stepped) {
      // A stepped load (KBC,1) takes its new value at the start of the load step, as in MAPDL:
      // the loads of this step at the time of the last point.
      ReducedPoint start = p;
      start.time = before.time;
      const VectorXd f_start = reduce(VectorXd(state.external_force(start).head(nf)));
      if (f_start != f_last) dynamics.jump_load(f_start);
    }
    const VectorXd f = reduce(VectorXd(state.external_force(p).head(nf)));
    dynamics.step(f);
    f_last = f;
    integration += std::chrono::duration<double>(clock::now() - t0).count();
    ++n_steps;
    ++stats.n_substeps;
    if (p.load_step != last_step) {
      ++stats.n_load_steps;
      last_step = p.load_step;
    }
    store(p);
    if (progress) {
      const auto& [end, count] = step_end[p.load_step];
      // One linear solve per step; the GP gap conditions' status changes are not counted (-1).
      // The whole axis is known here: the estimate covers every load step.
      progress->substep_done({stats.description, p.time, end, p.load_step, p.substep, count,
                              p.time - state.points[i - 1].time, 1, -1,
                              static_cast<long long>(state.points.size() - 1 - i),
                              state.points.back().time});
    }
  }
  seconds_per_step = n_steps ? integration / n_steps : 0.0;
  if (state.history->points_on_file() > 0)
    stats.notes.push_back(fmt::format(
        "state history: {} of {} points kept in a temporary file for the expansion pass "
        "(bounded memory)",
        state.history->points_on_file(), state.history->size()));
  stats.n_factorizations += dynamics.n_factorizations();
  stats.n_solves += dynamics.n_solves();
}

}  // namespace impactfe
