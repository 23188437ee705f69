#include "explicit/explicit_run.h"

#include <fmt/format.h>

#include <time.h>

#include <algorithm>
#include <cmath>
#include <limits>

#include "core/interruption.h"
#include "core/log.h"
#include "core/numbers.h"
#include "elements/element_registry.h"
#include "explicit/central_difference.h"
#include "explicit/explicit_contact.h"
#include "explicit/explicit_loads.h"
#include "explicit/part_energies.h"

namespace impactfe {

namespace {

/// CPU time of this thread (POSIX): the cost per element-cycle measured by it does not grow
/// when other processes share the cores, as wall time does.
double thread_cpu_seconds() {
  timespec t{};
  clock_gettime(CLOCK_THREAD_CPUTIME_ID, &t);
  return static_cast<double>(t.tv_sec) + 1e-9 * static_cast<double>(t.tv_nsec);
}

/// What the explicit solver does not carry out is refused before anything runs.
void refuse_unsupported(const Model& model, const AnalysisRequest& request) {
  for (const auto& [key, ic] : model.initial_conditions)
    if (ic.displacement != 0.0)
      throw NotImplementedError(ic.where, fmt::format("node {}: initial displacements are not "
                                                      "implemented in explicit dynamics",
                                                      key.node));
  for (const auto& [id, node] : model.nodes)
    if (node.rotated())
      throw NotImplementedError(request.where,
                                fmt::format("node {} has rotated nodal axes: explicit dynamics "
                                            "works in global axes only",
                                            id));
  for (const LoadStep& step : request.load_steps) {
    const auto refuse = [&](const std::string& what) {
      throw NotImplementedError(step.where,
                                fmt::format("load step {}: {} not implemented in explicit "
                                            "dynamics (D with value 0, ACEL, IC and EDVEL are)",
                                            step.number, what));
    };
    if (!step.forces.empty()) refuse("nodal forces (F) are");
    if (!step.pressures.empty()) refuse("surface loads (SF) are");
    if (step.rotation.any()) refuse("rotational inertia loads (OMEGA, DOMEGA, CGOMGA, DCGOMG) are");
    if (!step.constraint_tables.empty()) refuse("table (time-function) constraints are");
    for (const auto& t : step.acel_tables)
      if (!t.empty()) refuse("table (time-function) accelerations are");
    for (const auto& [key, value] : step.constraints)
      if (value != 0.0 && !is_rotation(key.dof))
        refuse(fmt::format("a prescribed displacement (D,{},{},{:g}) is", key.node,
                           dof_name(key.dof), value));
    if (!step.time_end || !(*step.time_end > 0.0))
      refuse("a load step without an end time (TIME) is");
  }
  const auto& damping = model.explicit_dynamics.mass_damping;
  if (damping && damping->curve > 0 && model.explicit_dynamics.curves.count(damping->curve) == 0)
    throw InputError(damping->where,
                     fmt::format("EDDAMP: curve {} no longer exists (EDCURVE)", damping->curve));
}

/// A rigid body moves by its EDMP constraint codes and the forces of its nodes: D on its nodes
/// and motion prescribed there by curve (EDLOAD VX, UX ...) would fight it and are refused.
void refuse_rigid_node_loads(const Model& model, const AnalysisRequest& request,
                             const ExplicitSystem& s) {
  if (s.rigid_bodies.empty()) return;
  const auto body_material = [&](int node) {
    const int n = s.index_of(node);
    return n >= 0 && s.is_rigid(static_cast<std::size_t>(n))
               ? s.rigid_bodies[static_cast<std::size_t>(
                                    s.rigid_body_of[static_cast<std::size_t>(n)])]
                     .material
               : 0;
  };
  for (const LoadStep& step : request.load_steps)
    for (const auto& [key, value] : step.constraints)
      if (const int mat = body_material(key.node))
        throw InputError(step.where,
                         fmt::format("load step {}: D,{},{} on a node of the rigid body of "
                                     "material {}: constrain a rigid body with EDMP,RIGID's "
                                     "VAL1 and VAL2",
                                     step.number, key.node, dof_name(key.dof), mat));
  for (const ExplicitCurveLoad& load : model.explicit_dynamics.loads)
    if ((load.label.size() == 2 && (load.label[0] == 'V' || load.label[0] == 'U')) ||
        load.label.rfind("ROT", 0) == 0 || load.label.rfind("OMG", 0) == 0)
      for (int node : load.nodes)
        if (const int mat = body_material(node))
          throw InputError(
              load.where,
              fmt::format("EDLOAD {} on node {} of the rigid body of material {}: {}", load.label,
                          node, mat,
                          load.label.size() == 2
                              ? "prescribe the motion of a rigid body on its part (EDLOAD RB" +
                                    load.label + " with the PART number)"
                              : std::string("a rigid body's rotation is not prescribed at its "
                                            "nodes (its RBR, RBO labels are not implemented)")));
  if (s.sets.empty())
    throw InputError(request.where,
                     "every element is rigid (EDMP,RIGID): an explicit run needs deformable "
                     "elements, whose wave speed sets the time step");
}

/// The fixed DOFs of a load step: D on UX, UY, UZ (value 0), or on ROTX, ROTY, ROTZ when
/// `rotations` (3 per node, about x y z). Rotations do not exist at the nodes of the explicit
/// solids, links and masses: D on them is ignored there.
std::vector<std::uint8_t> fixed_dofs(const ExplicitSystem& s, const LoadStep& step,
                                     bool rotations) {
  std::vector<std::uint8_t> fixed(3 * s.n_nodes(), 0);
  for (const auto& [key, value] : step.constraints) {
    const int n = s.index_of(key.node);
    if (n < 0 || is_rotation(key.dof) != rotations) continue;
    if (rotations && value != 0.0 &&
        std::binary_search(s.rotational_nodes.begin(), s.rotational_nodes.end(),
                           static_cast<std::size_t>(n)))
      throw NotImplementedError(step.where,
                                fmt::format("load step {}: a prescribed rotation (D,{},{},{:g}) "
                                            "is not implemented in explicit dynamics (D with "
                                            "value 0 fixes it)",
                                            step.number, key.node, dof_name(key.dof), value));
    fixed[3 * static_cast<std::size_t>(n) + static_cast<std::size_t>(key.dof) % 3] = 1;
  }
  return fixed;
}

/// A node with no mass (a COMBI165 end that no massive element shares) has no acceleration to
/// integrate: it must be held in x, y and z (D) or given a mass (MASS166), else it would stay
/// where it is whatever its spring pulls.
void refuse_free_massless_nodes(const Model& model, const ExplicitSystem& s, const LoadStep& step,
                                const std::vector<std::uint8_t>& fixed) {
  for (const auto& set : s.sets)
    for (std::size_t k = 0; k < set->size(); ++k)
      for (int a = 0; a < set->nodes_per_element(); ++a) {
        const auto n = static_cast<std::size_t>(set->nodes(k)[a]);
        if (s.mass[n] > 0.0 || s.is_rigid(n) ||
            (fixed[3 * n] && fixed[3 * n + 1] && fixed[3 * n + 2]))
          continue;
        const int id = set->element_id(k);
        const auto e = model.elements.find(id);
        throw InputError(e != model.elements.end() ? e->second.where : step.where,
                         fmt::format("load step {}: node {} of element {} has no mass and is not "
                                     "held in UX, UY and UZ: give it a mass (MASS166) or "
                                     "constrain it (D)",
                                     step.number, s.node_ids[n], id));
      }
}

/// IC velocities first, then EDVEL (which defines the velocity of its component's nodes). IC
/// on ROTX, ROTY, ROTZ sets the angular velocity of a shell or beam node; a nonzero one at a node
/// without rotations is refused.
void set_initial_velocities(const Model& model, const ExplicitSystem& s, CentralDifference& cd) {
  std::vector<Vec3> v(s.n_nodes(), Vec3::Zero()), w(s.n_nodes(), Vec3::Zero());
  for (const auto& [key, ic] : model.initial_conditions) {
    const int n = s.index_of(key.node);
    if (n < 0) continue;
    const auto node = static_cast<std::size_t>(n);
    if (!is_rotation(key.dof)) {
      v[node](static_cast<int>(key.dof)) = ic.velocity;
    } else if (cd.has_rotations(node)) {
      w[node](static_cast<int>(key.dof) - 3) = ic.velocity;
    } else if (ic.velocity != 0.0) {
      throw InputError(ic.where, fmt::format("node {}: an initial {} velocity: the node has no "
                                             "rotational DOFs in explicit dynamics (only the "
                                             "nodes of shells and beams have)",
                                             key.node, dof_name(key.dof)));
    }
  }
  for (const auto& e : model.explicit_dynamics.initial_velocities)
    for (int node : e.nodes) {
      const int n = s.index_of(node);
      if (n >= 0) v[static_cast<std::size_t>(n)] = e.velocity;
    }
  for (std::size_t n = 0; n < s.n_nodes(); ++n) {
    cd.set_velocity(n, v[n]);
    cd.set_angular_velocity(n, w[n]);
  }
}

/// One stored time point: nodal U, V, A and reactions in the file's node order, the contact
/// entities' forces, the parts' energies; the element results and the energies when `full`.
TimePoint make_point(const ExplicitSystem& s, const CentralDifference& cd,
                     const ExplicitContactSet& contact, const ExplicitPartEnergies& parts,
                     const std::vector<int>& file_nodes, int load_step, int point, bool full) {
  TimePoint p;
  p.time = cd.time();
  p.load_step = load_step;
  p.substep = point;
  const auto rows = static_cast<Eigen::Index>(file_nodes.size());
  for (auto* m : {&p.displacement, &p.velocity, &p.acceleration, &p.reaction})
    *m = Eigen::MatrixXd::Constant(rows, 6, kNaN);
  for (std::size_t n = 0; n < s.n_nodes(); ++n) {
    const int row = node_row(file_nodes, s.node_ids[n]);
    if (row < 0) continue;
    const Vec3 u = cd.displacement(n), v = cd.velocity(n), a = cd.acceleration(n),
               r = cd.reaction(n);
    for (int i = 0; i < 3; ++i) {
      p.displacement(row, i) = u(i);
      p.velocity(row, i) = v(i);
      p.acceleration(row, i) = a(i);
      if (cd.fixed(n, i)) p.reaction(row, i) = r(i);
    }
    if (!cd.has_rotations(n)) continue;
    const Vec3 rot = cd.rotation(n), w = cd.angular_velocity(n), b = cd.angular_acceleration(n),
               m = cd.moment_reaction(n);
    for (int i = 0; i < 3; ++i) {
      p.displacement(row, 3 + i) = rot(i);
      p.velocity(row, 3 + i) = w(i);
      p.acceleration(row, 3 + i) = b(i);
      if (cd.rotation_fixed(n, i)) p.reaction(row, 3 + i) = m(i);
    }
  }
  if (!contact.empty()) {
    const std::vector<double>& f = contact.interface_forces();
    p.contact_forces =
        Eigen::Map<const Eigen::VectorXd>(f.data(), static_cast<Eigen::Index>(f.size()));
  }
  p.part_energies = parts.at(s, cd);
  const ExplicitEnergies e = cd.energies();
  p.energy = {{"kinetic", e.kinetic},
              {"strain", e.internal - e.plastic_work},
              {"external_work", e.external_work},
              {"gap_work", e.contact},
              {"dissipation", e.hourglass + e.damping},
              {"plastic_work", e.plastic_work}};
  if (!full) return p;
  for (const auto& set : s.sets) {
    ElementResultTable table;
    for (std::size_t k = 0; k < set->size(); ++k) table.element_ids.push_back(set->element_id(k));
    const ElementTypeDescriptor* d = nullptr;
    for (const auto* t : registered_element_types())
      if (t->family == set->family()) d = t;
    table.item_names = d ? d->result_names : std::vector<std::string>{};
    set->results(table.values);
    p.element_results[set->family()] = std::move(table);
  }
  return p;
}

/// The energy check (same rule as the implicit driver's): |total − put in| beyond the bound
/// at kExplicitChecksOver checks in a row.
class EnergyCheck {
 public:
  explicit EnergyCheck(bool accept) : accept_(accept) {}
  void check(const CentralDifference& cd) {
    const ExplicitEnergies e = cd.energies();
    peak_ = std::max(peak_, e.put_in());
    const double reference = std::max(peak_, e.internal + e.kinetic);
    if (!(reference > 0.0) || cd.cycles() < kExplicitFirstJudgedCycle) return;
    last_ = std::abs(e.drift()) / reference;
    worst_ = std::max(worst_, last_);
    over_ = std::abs(e.drift()) > kExplicitEnergyBound * reference ? over_ + 1 : 0;
    if (over_ < kExplicitChecksOver || warned_) return;
    const std::string message = fmt::format(
        "t = {:g}, cycle {}: energy {}: kinetic + internal + hourglass + contact + damping {:.4g} "
        "against {:.4g} "
        "put in (initial kinetic + external work), {:.1f} % off (bound {:.0f} %, passed at {} "
        "checks in a row): an unstable time step (EDCTS TSSFAC above 1 or a stiff element "
        "outside the step estimate) or an hourglass mode out of control (EDHGLS, EDMP,HGLS). "
        "The results up to here are kept; --accept-energy-error goes on",
        cd.time(), cd.cycles(), e.drift() > 0 ? "created" : "lost",
        e.kinetic + e.internal + e.hourglass + e.contact + e.damping, e.put_in(),
        100.0 * std::abs(e.drift()) / reference, 100.0 * kExplicitEnergyBound, kExplicitChecksOver);
    if (!accept_) throw SolutionError(message);
    Log::warn("{} (accepted: --accept-energy-error)", message);
    warned_ = true;
  }
  double worst() const { return worst_; }
  /// The error of the last check that judged the balance (NaN before the first).
  double last() const { return last_; }

 private:
  bool accept_;
  bool warned_ = false;
  int over_ = 0;
  double last_ = std::numeric_limits<double>::quiet_NaN();
  double peak_ = 0.0, worst_ = 0.0;
};

void summarize(const ExplicitSystem& s, const CentralDifference& cd, const EnergyCheck& check,
               ExplicitRunSummary& out) {
  const ExplicitEnergies e = cd.energies();
  out.notes.push_back(fmt::format(
      "explicit: {} cycles, {} elements, {} nodes; last step {:.4g} (element {}), smallest {:.4g} "
      "(element {}); {:.0f} ns (CPU) per element-cycle",
      out.cycles, out.n_elements, out.n_nodes, out.last_step, out.last_controlling_element,
      out.smallest_step, out.smallest_step_element, out.ns_per_element_cycle));
  out.notes.push_back(fmt::format(
      "energy: kinetic {:.6g}, internal {:.6g} (plastic work {:.4g}), hourglass {:.4g} ({:.2f} % "
      "of internal), contact {:.4g}, initial kinetic {:.6g}, external work {:.6g}; balance off "
      "by {:.3f} % (largest {:.3f} %)",
      e.kinetic, e.internal, e.plastic_work, e.hourglass,
      e.internal > 0 ? 100.0 * e.hourglass / e.internal : 0.0, e.contact, e.initial_kinetic,
      e.external_work, e.put_in() > 0 ? 100.0 * e.drift() / e.put_in() : 0.0,
      100.0 * check.worst()));
  if (e.damping > 0.0)
    out.notes.push_back(
        fmt::format("mass-weighted damping (EDDAMP): {:.6g} dissipated ({:.2f} % of the energy "
                    "put in)",
                    e.damping, e.put_in() > 0 ? 100.0 * e.damping / e.put_in() : 0.0));
  if (cd.added_mass() > 0.0)
    out.notes.push_back(fmt::format("mass scaling (EDCTS DTMS): {:.4g} added to {:.4g} ({:.3f} %)",
                                    cd.added_mass(), s.physical_mass,
                                    100.0 * cd.added_mass() / s.physical_mass));
}

/// The store times of an interval over [0, end]: multiples of `interval` (and the end).
struct OutputGrid {
  double interval = 0.0;
  long next = 1;  // the next multiple to store
  bool due(double t) const { return interval > 0.0 && t >= next * interval * (1.0 - 1e-9); }
  void advance(double t) {
    while (due(t)) ++next;
  }
};

}  // namespace

ExplicitRunSummary run_explicit_analysis(const Model& model, const AnalysisRequest& request,
                                         ResultsWriter& writer, const ExplicitRunOptions& options) {
  refuse_unsupported(model, request);
  ExplicitSystem system = build_explicit_system(model);
  refuse_rigid_node_loads(model, request, system);
  const ExplicitControls& controls = model.explicit_dynamics;
  CentralDifference cd(system, controls);
  ExplicitCurveLoads loads(system, controls);
  if (!loads.empty()) cd.add_interaction(&loads);
  ExplicitContactSet contact(model, system);
  if (!contact.empty()) cd.add_interaction(&contact);
  const ExplicitPartEnergies parts(model, system);
  set_initial_velocities(model, system, cd);
  const double end = *request.load_steps.back().time_end;
  OutputGrid results{controls.results.for_end_time(end, 100)};
  // EDHTIME: energy checks at its interval; stored points (nodal, energies) when it or EDHIST
  // is given.
  OutputGrid history{controls.history.for_end_time(end, 1000)};
  // EDHIST asks for history points too (at the default interval without EDHTIME); they hold
  // every node, the components' among them.
  const bool store_history =
      controls.history.steps || controls.history.interval || !controls.history_components.empty();
  writer.begin_analysis(ResultsKind::Transient, "explicit dynamics (central difference)",
                        static_cast<long long>(end / results.interval) + 2);
  ExplicitRunSummary summary;
  summary.n_elements = system.n_elements();
  summary.n_nodes = system.n_nodes();
  summary.smallest_step = std::numeric_limits<double>::infinity();
  EnergyCheck check(options.accept_energy_error);
  StopPoints stop_points;
  double loop_seconds = 0.0;
  int point = 0;
  for (std::size_t i = 0; i < request.load_steps.size(); ++i) {
    const LoadStep& step = request.load_steps[i];
    std::vector<std::uint8_t> fixed = fixed_dofs(system, step, false);
    refuse_free_massless_nodes(model, system, step, fixed);
    cd.set_loads(std::move(fixed), step.acel);
    if (system.has_rotations()) cd.set_rotation_fixes(fixed_dofs(system, step, true));
    if (i == 0) {
      cd.start();
      // The initial state is load step 0, substep 0, as the implicit transients store it.
      writer.append(make_point(system, cd, contact, parts, writer.node_ids(), 0, 0, true));
    }
    const double step_end = *step.time_end;
    const double start = thread_cpu_seconds();
    while (cd.time() < step_end * (1.0 - 1e-12)) {
      const double dt = std::min(cd.stable_step(), step_end - cd.time());
      if (cd.stable_step() < summary.smallest_step) {
        summary.smallest_step = cd.stable_step();
        summary.smallest_step_element = cd.controlling_element();
      }
      cd.cycle(dt);
      const bool last = cd.time() >= step_end * (1.0 - 1e-12);
      if (options.progress && (last || cd.cycles() % kProgressCycles == 0))
        options.progress(
            {cd.time(), step_end, end, step.number, last, cd.cycles(), dt, check.last()});
      const bool full = results.due(cd.time()) || last;
      const bool partial = history.due(cd.time());
      if (full || partial) {
        loop_seconds += thread_cpu_seconds() - start;
        check.check(cd);
        if (full || store_history)
          writer.append(make_point(system, cd, contact, parts, writer.node_ids(), step.number,
                                   ++point, full));
        results.advance(cd.time());
        history.advance(cd.time());
        if (const int signal = stop_requested())
          throw RunInterrupted(signal, fmt::format("explicit run stopped by {} at t = {:g}",
                                                   signal_name(signal), cd.time()));
        loop_seconds -= thread_cpu_seconds() - start;
      }
    }
    loop_seconds += thread_cpu_seconds() - start;
  }
  summary.cycles = cd.cycles();
  summary.element_cycles = cd.cycles() * static_cast<long>(system.n_elements());
  summary.last_step = cd.stable_step();
  summary.last_controlling_element = cd.controlling_element();
  summary.stored_points = point + 1;
  summary.ns_per_element_cycle =
      summary.element_cycles > 0 ? 1e9 * loop_seconds / static_cast<double>(summary.element_cycles)
                                 : 0.0;
  summarize(system, cd, check, summary);
  if (!contact.empty()) summary.notes.push_back(contact.summary());
  writer.set_count("cycles", summary.cycles);
  writer.set_attribute("ns_per_element_cycle", summary.ns_per_element_cycle);
  writer.set_attribute("added_mass", cd.added_mass());
  writer.set_attribute("hourglass_energy", cd.energies().hourglass);
  return summary;
}

}  // namespace impactfe
