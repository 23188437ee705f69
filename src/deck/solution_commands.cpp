// Solution commands: load-step options, analysis options (4x and modern), load-step closing
// (LWRITE, AFWRITE, /INPUT,27, SOLVE, LSWRITE, LSSOLVE) and expansion passes (/STRESS, EXPASS).
#include <fmt/format.h>

#include <algorithm>
#include <cmath>
#include <limits>

#include "core/files.h"
#include "deck/deck_context.h"
#include "deck/model_changes.h"
#include "deck/post_support.h"
#include "results/output_selection.h"
#include "time/time_schedule.h"

namespace impactfe::deck {

namespace {

/// ITER NPRINT / OUTPR ask for a solution printout in the output listing; impactfe writes every
/// result to the results file instead (printed with PRNSOL / PRESOL / PRVAR).
void log_no_printout(const Command& c) {
  Log::info(
      "{}:{}: {}: no solution printout is produced; results are in the results file (print them "
      "with PRNSOL / PRESOL / PRVAR or `impactfe post`)",
      c.where.file, c.where.line, c.name);
}

// ---- time and substeps -----------------------------------------------------------------------

void stress_time(DeckReader& r, const Command& c) {
  // /STRESS group: NSTRES solutions evenly spaced in (T_prev, T] (§3.26).
  const auto t = r.opt_real(c, 1);
  if (!t) r.fail(c, "TIME value missing");
  if (*t <= r.solution.stress_t_prev)
    r.fail(c, fmt::format("TIME {} is not greater than the previous expansion time {}", *t,
                          r.solution.stress_t_prev));
  r.solution.stress_requests.push_back(
      ExpansionRequest{r.solution.stress_count, r.solution.stress_t_prev, *t, false});
  r.solution.stress_t_prev = *t;
  r.solution.stress_count = 1;
}

void cmd_time(DeckReader& r, const Command& c) {
  if (r.processor == kStress) {
    stress_time(r, c);
    return;
  }
  const auto t = r.opt_real(c, 1);
  if (t && *t < 0.0) r.fail(c, fmt::format("TIME {} is negative", *t));
  const auto prev = r.previous_time();
  if (t && prev && *t <= *prev)
    r.fail(c, fmt::format("TIME {} is not greater than the previous load step's TIME {} (TIME "
                          "must increase)",
                          *t, *prev));
  r.model.current.time_end = t;
}

// DTIME / DELTIM and NSUBST store what the deck says; the time schedule owns the rules
// (check_step_size_settings, time/time_schedule.h), applied here so that an error names the
// command.

void cmd_dtime(DeckReader& r, const Command& c) {
  const auto dt = r.opt_real(c, 1);
  if (!dt) r.fail(c, "time step value missing");
  LoadStep& s = r.model.current;
  s.dt = *dt;
  // DTIME/DELTIM and NSUBST/ITER are alternatives: the last one given wins (KAN=5 keeps both;
  // its NITTER is not used for the step size).
  if (!(r.dialect == Dialect::Classic4x && r.solution.kan == 5)) s.n_substeps.reset();
  // DELTIM,DTIME,DTMIN,DTMAX,Carry: the limits of automatic time stepping (APDL_MODELING
  // §9.1); they replace those of an earlier NSUBST (the last of the two wins).
  StepControl& sc = s.control;
  sc = StepControl{sc.automatic};
  if (c.name == "DELTIM") {  // 4.2 DTIME has the step only
    sc.dt_min = r.opt_real(c, 2);
    sc.dt_max = r.opt_real(c, 3);
  }
  check_step_size_settings(s, c.where);
  if (c.name == "DELTIM") sc.carry = r.on_off(c, 4, false);
}

void cmd_nsubst(DeckReader& r, const Command& c) {
  const auto n = r.opt_int(c, 1);
  if (!n) r.fail(c, "number of substeps missing");
  LoadStep& s = r.model.current;
  s.n_substeps = *n;
  s.dt.reset();
  // NSUBST,NSBSTP,NSBMX,NSBMN,Carry: NSBMX substeps give the smallest step, NSBMN the largest
  // (APDL_MODELING §9.1); they replace the limits of an earlier DELTIM.
  StepControl& sc = s.control;
  sc = StepControl{sc.automatic};
  sc.n_max = r.opt_int(c, 2);
  sc.n_min = r.opt_int(c, 3);
  check_step_size_settings(s, c.where);
  sc.carry = r.on_off(c, 4, false);
}

void cmd_iter(DeckReader& r, const Command& c) {
  if (r.processor == kStress) return;  // NPRINT/NPOST of the expansion pass: printing only
  const auto n = r.opt_int(c, 1);
  const int nitter = n.value_or(1);
  if (nitter < 0) r.fail(c, "negative NITTER (iterate to convergence) is not supported");
  if (nitter == 0) r.fail(c, "zero substeps: NITTER must be positive");
  LoadStep& s = r.model.current;
  if (r.solution.kan == 0) {
    r.model.options.convergence.max_iterations = nitter;  // §3.16: static → equilibrium iterations
  } else {
    s.n_substeps = nitter;
    if (r.solution.kan == 4) s.dt.reset();
  }
  const int nprint = r.integer(c, 2, 0);
  const int npost = r.integer(c, 3, 0);
  if (nprint < 0 || npost < 0) r.fail(c, "NPRINT/NPOST must not be negative");
  s.output = OutputControl{};  // NPOST is the frequency of every item (no per-item OUTRES)
  s.output.every = npost;
  if (nprint > 0) log_no_printout(c);
  // Kept as given (n = every n-th substep and the last): under KAN=5 NITTER is not the
  // number of steps, so "NPOST >= NITTER" must not be read as "last only".
}

void cmd_autots(DeckReader& r, const Command& c) {
  const std::string l = r.label(c, 1);
  // AUTOTS,ON / AUTO: bisection and step growth (APDL_MODELING §9.1, §9.3); blank = ON.
  if (l == "ON" || l == "AUTO" || l == "1" || l.empty())
    r.model.current.control.automatic = true;
  else if (l == "OFF" || l == "0")
    r.model.current.control.automatic = false;
  else
    r.fail(c, fmt::format("bad key '{}' (ON, OFF, AUTO)", c.text(1)));
}

void cmd_kbc(DeckReader& r, const Command& c) {
  const int k = r.integer(c, 1, 0);
  if (k != 0 && k != 1) r.fail(c, fmt::format("KBC key {} must be 0 (ramped) or 1 (stepped)", k));
  r.model.current.stepped = k == 1;
}

void cmd_timint(DeckReader& r, const Command& c) {
  r.model.current.time_integration = r.on_off(c, 1, true);
}

void cmd_nlgeom(DeckReader& r, const Command& c) {
  const bool on = r.on_off(c, 1, false);
  r.model.options.large_deflection = on;
  if (on) r.model.options.stress_stiffening = true;
}

void cmd_rate(DeckReader& r, const Command& c) {
  // RATE,Option: implicit creep (TB,CREEP) acts in the load steps solved while it is ON; OFF
  // (the default) solves them without creep (MAPDL Command Reference, RATE).
  r.solution.creep_rate = r.on_off(c, 1, false);
  // The Verification Manual's creep decks write RATE,ON,ON: a second ON/OFF that the command
  // reference does not describe; accepted as the first field's repetition, anything else refused.
  if (!c.blank(2) && r.on_off(c, 2, false) != r.solution.creep_rate)
    r.fail(c, fmt::format("field 2 '{}' differs from the option '{}' (RATE,Option)", c.text(2),
                          c.text(1)));
  for (int f = 3; f <= c.n_fields(); ++f)
    if (!c.blank(f)) r.fail(c, fmt::format("field {} '{}' is not a RATE field", f, c.text(f)));
}

void cmd_toff(DeckReader& r, const Command& c) {
  // TOFF,Value: the offset of the temperature scale from absolute zero (blank: 0); the creep
  // laws' temperature terms e^(−C/T) read T + TOFF (MAPDL Command Reference, TOFF). Kept with
  // RATE: both arm the creep clock at SOLVE (arm_creep_clock).
  r.solution.temperature_offset = r.real(c, 1, 0.0);
}

void cmd_stef(DeckReader& r, const Command& c) {
  // STEF,VALUE: the Stefan-Boltzmann constant (blank: MAPDL's 0.119E-10). Thermal archives
  // (CDWRITE) state it; it enters radiation only, which impactfe does not model.
  const double value = r.real(c, 1, 0.119e-10);
  if (!(value > 0.0)) r.fail(c, fmt::format("VALUE {} must be positive", value));
  r.solution.stefan_boltzmann = value;
}

void cmd_sstif(DeckReader& r, const Command& c) {
  r.model.options.stress_stiffening = r.on_off(c, 1, false);
}

void cmd_lumpm(DeckReader& r, const Command& c) {
  r.model.options.lumped_mass = r.on_off(c, 1, false);
}

void cmd_eresx(DeckReader& r, const Command& c) {
  // ERESX,Key: DEFA (MAPDL's default: extrapolated while elastic, the nearest point copied
  // once inelastic), YES (copied), NO (extrapolated); ON and OFF as YES and NO. Carried out by
  // PLANE182/183; SOLVE refuses it with the other elements that give nodal values.
  const std::string key = r.label(c, 1);
  if (key.empty() || key == "DEFA")
    r.model.options.nodal_stresses = NodalStressRule::Default;
  else if (key == "YES" || key == "ON")
    r.model.options.nodal_stresses = NodalStressRule::Copy;
  else if (key == "NO" || key == "OFF")
    r.model.options.nodal_stresses = NodalStressRule::Extrapolate;
  else
    r.fail(c, fmt::format("Key '{}': DEFA, YES or NO", c.text(1)));
}

// ---- analysis type and method ------------------------------------------------------------------

void cmd_antype(DeckReader& r, const Command& c) {
  const std::string l = r.label(c, 1);
  // The label or its number; MAPDL also reads an abbreviation of at least four characters
  // (ANTYPE,SUBST, TRAN).
  const auto is = [&](const char* number, std::initializer_list<const char*> names) {
    if (l == number) return true;
    for (const char* name : names)
      if (l == name || (l.size() >= 4 && std::string(name).rfind(l, 0) == 0)) return true;
    return false;
  };
  AnalysisType type = r.model.options.type;
  if (is("0", {"STATIC"}))
    type = AnalysisType::Static;
  else if (is("2", {"MODAL"}))
    type = AnalysisType::Modal;
  else if (is("4", {"TRANSIENT"}))
    type = AnalysisType::Transient;
  else if (is("7", {"SUBSTR", "SUBSTRUCTURE"}))
    type = AnalysisType::Substructure;
  else if (is("3", {"HARMIC", "HARMONIC"}))
    type = AnalysisType::Harmonic;
  else if (is("8", {"SPECTR", "SPECTRUM"})) {
    // The spectrum analysis works on the modes of the modal analysis solved before it.
    if (r.model.modal_load_vectors.empty())
      r.fail(c, "a spectrum analysis needs the modal analysis (ANTYPE,MODAL ... SOLVE) first");
    type = AnalysisType::Spectrum;
  } else if (is("1", {"BUCKLE"}))
    r.fail(c, "buckling analysis (ANTYPE,BUCKLE) is not supported");
  else if (l.empty())
    ;
  else
    r.fail(c, fmt::format("analysis type '{}' not supported (STATIC, MODAL, HARMIC, TRANS, SUBSTR)",
                          c.text(1)));
  const std::string status = r.label(c, 2);
  const bool restart = status == "REST" || status == "RESTART";
  if (!status.empty() && status != "NEW" && !restart)
    r.fail(c, fmt::format("ANTYPE status '{}' not supported (NEW, RESTART)", c.text(2)));
  if (restart) {
    // Multiframe restart (APDL_MODELING §9.5): the next SOLVE continues the run saved in
    // <jobname>.rst.h5 from the point LDSTEP, SUBSTEP (blank: the last one saved).
    if (type != AnalysisType::Transient && type != AnalysisType::Static)
      r.fail(c, "RESTART needs a static or full transient analysis (ANTYPE,TRANS or STATIC)");
    const std::string action = r.label(c, 5);
    if (!action.empty() && action != "CONT" && action != "CONTINUE")
      r.fail(c, fmt::format("restart action '{}' not supported (CONTINUE)", c.text(5)));
    RestartRequest q;
    q.load_step = r.opt_int(c, 3);
    q.substep = r.opt_int(c, 4);
    if ((q.load_step && *q.load_step <= 0) || (q.substep && *q.substep <= 0))
      r.fail(c, "LDSTEP and SUBSTEP must be positive");
    q.where = c.where;
    r.model.options.restart = q;
    r.solution.open_analysis.reset();  // the restarted run is an analysis of its own
  } else {
    r.model.options.restart.reset();
    if (type != r.model.options.type) r.solution.open_analysis.reset();
    // A new analysis: the expansion pass of the previous one (EXPASS,ON) is over, so its SOLVE
    // solves this analysis instead of expanding again.
    r.solution.expass = false;
    // LVSCALE loads one mode-superposition analysis; a new analysis starts without it.
    r.model.current.load_vector_scale = 0.0;
  }
  r.model.options.type = type;
}

/// OUTRES/OUTPR frequency: n, ALL (1), LAST (0), NONE (-1); blank: every substep for a
/// transient, the last otherwise.
int output_frequency(DeckReader& r, const Command& c) {
  const std::string f = r.label(c, 2);
  if (r.label(c, 1) == "ERASE") return 0;
  if (f.empty()) return r.model.options.type == AnalysisType::Transient ? 1 : 0;
  if (f == "ALL") return 1;
  if (f == "LAST") return 0;
  if (f == "NONE") return -1;
  const int n = r.integer(c, 2, 1);
  if (n < 0) {
    r.warn(c, "-n (auto time stepping) taken as every substep");
    return 1;
  }
  return n;
}

/// The OUTRES items an Item label stands for (APDL_SCRIPTING §E.8); empty for an item impactfe
/// writes no results of (warned), an error for a label OUTRES does not know.
std::vector<OutputItem> output_items(DeckReader& r, const Command& c, const std::string& item) {
  using I = OutputItem;
  if (item == "NSOL") return {I::NSOL};
  if (item == "V" || item == "VSOL") return {I::VSOL};
  if (item == "A" || item == "ASOL") return {I::ASOL};
  if (item == "RSOL") return {I::RSOL};
  if (item == "ESOL") return {I::STRS, I::EPEL, I::MISC};
  if (item == "STRS") return {I::STRS};
  if (item == "EPEL") return {I::EPEL};
  if (item == "MISC" || item == "NLOAD") return {I::MISC};
  if (item == "BASIC") return {I::NSOL, I::RSOL, I::STRS};
  for (const char* other : {"EPPL", "EPTH", "EPCR", "EPDI", "FGRAD", "FFLUX", "LOCI", "SVAR",
                            "VENG", "CINT", "FSOL", "NAR", "CONT", "ETMP", "SRFS", "EANGL"})
    if (item == other) {
      r.warn(c, fmt::format("Item {}: impactfe writes no such results; nothing to control", item));
      return {};
    }
  r.fail(c, fmt::format("unknown Item {} (ALL, BASIC, NSOL, V, A, RSOL, ESOL, STRS, EPEL, MISC, "
                        "NLOAD, ERASE, STAT)",
                        c.text(1)));
}

bool nodal_output_item(OutputItem i) {
  return i == OutputItem::NSOL || i == OutputItem::VSOL || i == OutputItem::ASOL ||
         i == OutputItem::RSOL;
}

void cmd_outres(DeckReader& r, const Command& c) {
  // OUTRES,Item,Freq,Cname: specifications accumulate per item, a later one winning for the
  // nodes / elements it covers (APDL_SCRIPTING §E.8; docs/results_file.md "Output control").
  OutputControl out = r.model.current.output;
  const std::string item = r.label(c, 1);
  if (item == "STAT") {
    r.output.print(" OUTRES settings of the current load step:");
    for (const auto& line : describe_output(out)) r.output.print("   " + line);
    return;
  }
  const int every = output_frequency(r, c);
  const std::string cname = r.label(c, 3);
  if (item == "ERASE") {
    if (!cname.empty()) r.fail(c, "ERASE takes no Cname");
    r.model.current.output = OutputControl{};
    return;
  }
  if ((item.empty() || item == "ALL") && (cname.empty() || cname == "ALL")) {
    r.model.current.output = OutputControl{};
    r.model.current.output.every = every;
    return;
  }
  std::vector<OutputItem> items =
      item.empty() || item == "ALL"
          ? std::vector<OutputItem>{OutputItem::NSOL, OutputItem::VSOL, OutputItem::ASOL,
                                    OutputItem::RSOL, OutputItem::STRS, OutputItem::EPEL,
                                    OutputItem::MISC}
          : output_items(r, c, item);
  OutputSpec spec{every, {}, {}};
  if (!cname.empty() && cname != "ALL") {
    const auto it = r.model.components.find(cname);
    if (it == r.model.components.end())
      r.fail(c, fmt::format("Cname {}: no such component (CM)", c.text(3)));
    const Component& comp = it->second;
    if (comp.entity != "NODE" && comp.entity != "ELEM")
      r.fail(c, fmt::format("Cname {} is a {} component; OUTRES takes a node or element component",
                            c.text(3), comp.entity));
    // A node component restricts the nodal items of Item, an element component its element
    // items; the other items keep their settings.
    const bool nodal = comp.entity == "NODE";
    std::erase_if(items, [&](OutputItem i) { return nodal_output_item(i) != nodal; });
    if (items.empty())
      r.fail(c, fmt::format("Cname {} is a {} component, Item {} has only {} results", c.text(3),
                            nodal ? "node" : "element", item, nodal ? "element" : "nodal"));
    spec.component = cname;
    spec.ids = comp.ids;
  }
  for (OutputItem i : items) {
    auto& specs = out.items[static_cast<std::size_t>(i)];
    if (spec.component.empty()) {
      specs.assign(1, spec);  // covers every node / element: replaces what came before
      continue;
    }
    if (specs.empty()) specs.push_back(OutputSpec{out.every, {}, {}});
    std::erase_if(specs, [&](const OutputSpec& s) { return s.component == spec.component; });
    specs.push_back(spec);
  }
  r.model.current.output = std::move(out);
}

void cmd_outpr(DeckReader& r, const Command& c) {
  output_frequency(r, c);  // validates the fields
  log_no_printout(c);
}

void cmd_seopt(DeckReader& r, const Command& c) {
  AnalysisOptions& o = r.model.options;
  if (!c.blank(1)) {
    if (const std::string problem = jobname_problem(c.text(1), "Sename"); !problem.empty())
      r.fail(c, problem);
    o.superelement_name = c.text(1);
  }
  const int sematr = r.integer(c, 2, 1);
  if (sematr < 1 || sematr > 3) r.fail(c, fmt::format("SEMATR {} must be 1, 2 or 3", sematr));
  o.superelement_matrices = sematr;
  if (!c.blank(4)) o.stress_stiffening = r.integer(c, 4, 0) != 0;
}

void cmd_seexp(DeckReader& r, const Command& c) {
  // SEEXP,Sename,Usefil,Imagky,Expopt (APDL_SCRIPTING §E.14).
  if (c.blank(1)) r.fail(c, "Sename (the superelement to expand) missing");
  if (c.blank(2)) r.fail(c, "Usefil (the results file of the use pass) missing");
  const std::string imagky = r.label(c, 3);
  if (!imagky.empty() && imagky != "REAL" && imagky != "0")
    r.fail(c, fmt::format("Imagky '{}': only real solutions exist here (no harmonic analyses)",
                          c.text(3)));
  const std::string expopt = r.label(c, 4);
  if (!expopt.empty() && expopt != "ON")
    r.fail(c, fmt::format("Expopt '{}' not supported: the master DOF values of the use pass are "
                          "always part of the expanded results (ON)",
                          c.text(4)));
  r.solution.seexp = SuperelementExpansionSource{c.text(1), c.text(2), c.where};
}

void cmd_cmsopt(DeckReader& r, const Command& c) {
  r.fail(c, "component mode synthesis (CMSOPT) is not implemented");
}

// ---- load steps and analyses -----------------------------------------------------------------

/// The current load state as load step `number`, closed by command `c`.
LoadStep snapshot(DeckReader& r, const Command& c, int number) {
  LoadStep s = r.model.current;
  s.number = number;
  s.where = c.where;
  return s;
}

void check_increasing(DeckReader& r, const Command& c, const std::vector<LoadStep>& previous,
                      const LoadStep& s) {
  if (previous.empty() || !s.time_end) return;
  std::optional<double> prev;
  for (const auto& p : previous)
    if (p.time_end && (!prev || *p.time_end > *prev)) prev = p.time_end;
  if (prev && *s.time_end <= *prev)
    r.fail(c, fmt::format("load step {} ends at TIME {}, not after the previous step ({}); "
                          "TIME must increase",
                          s.number, *s.time_end, *prev));
}

void cmd_lwrite(DeckReader& r, const Command& c) {
  if (r.solution.frozen) r.fail(c, "LWRITE after AFWRITE: the analysis file is already written");
  LoadStep s = snapshot(r, c, static_cast<int>(r.solution.load_steps_4x.size()) + 1);
  check_increasing(r, c, r.solution.load_steps_4x, s);
  r.solution.load_steps_4x.push_back(std::move(s));
}

void cmd_afwrite(DeckReader& r, const Command& c) {
  if (r.solution.frozen) r.fail(c, "AFWRITE issued twice");
  if (r.solution.load_steps_4x.empty())
    r.solution.load_steps_4x.push_back(snapshot(r, c, 1));  // §3.25
  r.validate_elements();
  if (r.solution.kan == 5 && r.model.masters.empty())
    r.fail(c, "KAN=5 (reduced transient) needs master DOFs (M)");
  if (r.solution.kan == 7 && r.model.masters.empty())
    r.fail(c, "KAN=7 (substructure generation) needs master DOFs (M)");
  if (r.solution.kan == 4 && !r.model.masters.empty())
    r.warn(c, fmt::format("{} master DOFs ignored in a full transient (KAN=4)",
                          r.model.masters.size()));
  for (const auto& [key, value] : r.model.options.kay)
    Log::info("KAY({}) = {} (KAN={})", key, value, r.solution.kan);
  Job::Step step;
  AnalysisRequest a;
  a.options = r.model.options;
  a.load_steps = r.solution.load_steps_4x;
  a.where = c.where;
  a.complete = true;
  step.analysis = std::move(a);
  step.model_snapshot = std::make_shared<Model>(solution_model(r, c));
  r.solution.frozen = std::move(step);
}

void cmd_exec(DeckReader& r, const Command&) {
  r.solution.exec_armed = true;
  r.processor = kSolu;
}

/// Opens a modern analysis (one Job::Step) if none is open.
AnalysisRequest& open_analysis(DeckReader& r, const Command& c) {
  if (!r.solution.open_analysis) {
    r.validate_elements();
    if (r.model.options.type == AnalysisType::Transient &&
        r.model.options.method == TransientMethod::Reduced && r.model.masters.empty())
      r.fail(c, "a reduced transient (TRNOPT,REDUC) needs master DOFs (M)");
    Job::Step step;
    AnalysisRequest a;
    a.options = r.model.options;
    r.model.options.restart.reset();  // ANTYPE,,RESTART is taken by this analysis only
    a.where = c.where;
    // After FINISH, a SOLVE without ANTYPE,,REST starts the analysis again (a restart continues
    // the earlier one instead and adds to its results file).
    const bool new_analysis = r.solution.finished_analysis && !a.options.restart;
    r.solution.finished_analysis = false;
    step.analysis = std::move(a);
    step.model_snapshot = std::make_shared<Model>(solution_model(r, c));
    r.job.steps.push_back(std::move(step));
    r.solution.open_analysis = r.job.steps.size() - 1;
    if (new_analysis && r.options.host != nullptr)
      r.options.host->begin_new_analysis(r.job, *r.solution.open_analysis);
  }
  return *r.job.steps[*r.solution.open_analysis].analysis;
}

/// Appends the current load state as the next load step of the open analysis (not solved yet).
void append_current(DeckReader& r, const Command& c) {
  prepare_model_for_solution(r, c);
  if (r.solution.open_analysis) {
    const Job::Step& open = r.job.steps[*r.solution.open_analysis];
    if (const std::string change = model_change(*open.model_snapshot, r.model); !change.empty())
      r.fail(c, fmt::format("{} since this analysis began at {}: an analysis keeps the model of "
                            "its first SOLVE, so the change would not act on this load step. "
                            "Make it before the analysis, or start a new analysis (/CLEAR, or "
                            "ANTYPE of another type)",
                            change, location_text(open.analysis->where)));
  }
  AnalysisRequest& a = open_analysis(r, c);
  // The Newton settings are the analysis's, taken at its first SOLVE: a change made later does
  // not act, and is said (not refused: decks tighten CNVTOL between load steps harmlessly).
  const ConvergenceOptions& taken = a.options.convergence;
  const ConvergenceOptions& now = r.model.options.convergence;
  if (!a.load_steps.empty() &&
      (taken.max_iterations != now.max_iterations || taken.force_tolerance != now.force_tolerance ||
       taken.force_minref != now.force_minref ||
       taken.displacement_tolerance != now.displacement_tolerance ||
       taken.full_newton != now.full_newton || taken.line_search != now.line_search ||
       taken.line_search_auto != now.line_search_auto))
    r.warn(c, fmt::format(
                  "CNVTOL, NEQIT, NROPT or LNSRCH changed since this analysis began at {}: the "
                  "analysis keeps the convergence settings of its first SOLVE for all "
                  "its load steps",
                  location_text(a.where)));
  LoadStep s = snapshot(r, c, static_cast<int>(a.load_steps.size()) + 1);
  check_increasing(r, c, a.load_steps, s);
  // The rotational inertia loads enter the load vector of the static and full transient
  // solutions (analysis/step_loads.cpp); the modal, harmonic, reduced, mode-superposition and
  // substructure analyses would ignore them, so they are refused there.
  const bool incremental =
      a.options.type == AnalysisType::Static ||
      (a.options.type == AnalysisType::Transient && a.options.method == TransientMethod::Full);
  if (s.rotation.any() && !incremental)
    r.fail(c, fmt::format("the rotational inertia loads (OMEGA, DOMEGA, CGOMGA, DCGOMG; the last "
                          "given at {}) are carried out in static and full transient analyses "
                          "only, not in this one",
                          location_text(s.rotation.where)));
  // ERESX other than DEFA is carried out by the 2-D solids only: refused where another element
  // would extrapolate (or copy) by its own rule.
  if (r.model.options.nodal_stresses != NodalStressRule::Default)
    for (const auto& [id, type] : r.model.element_types)
      for (const char* other :
           {"SOLID45", "SOLID185", "SOLID186", "SOLID187", "SOLID95", "SHELL208", "SHELL281"})
        if (type.ansys_name == other)
          r.fail(c, fmt::format("ERESX,YES/NO is carried out for PLANE182/183 only; element "
                                "type {} is {}, whose nodal values follow MAPDL's default",
                                id, other));
  a.load_steps.push_back(std::move(s));
  if (a.load_steps.back().time_end) r.solution.last_solved_time = a.load_steps.back().time_end;
}

/// The creep clock of the analysis about to solve (shared by the creep laws of its elements):
/// creep acts when RATE is ON, at the absolute temperature TUNIF (else TREF) + TOFF of the load
/// step. The solution driver sets the substep's time and step on it (DirectSolution).
void arm_creep_clock(DeckReader& r, const Job::Step& step) {
  CreepClock& clock = *step.model_snapshot->creep_clock;
  clock.active = r.solution.creep_rate;
  clock.temperature =
      r.model.current.uniform_temperature.value_or(r.model.current.reference_temperature) +
      r.solution.temperature_offset;
  clock.dt = 0.0;
}

void solve_current(DeckReader& r, const Command& c) {
  append_current(r, c);
  AnalysisRequest& a = *r.job.steps[*r.solution.open_analysis].analysis;
  if (a.options.type == AnalysisType::Modal) r.model.modal_load_vectors = a.load_steps;
  if (a.options.type == AnalysisType::Spectrum) {
    // The modes are those of the modal analysis: its constraints, not the D given since (a
    // spectrum analysis has no load step of its own).
    if (r.model.modal_load_vectors.empty())
      r.fail(c, "a spectrum analysis needs the modal analysis (ANTYPE,MODAL ... SOLVE) first");
    if (a.load_steps.size() > 1)
      r.fail(c, "a spectrum analysis is solved once; start another with ANTYPE,SPECTR");
    const SpectrumOptions& s = a.options.spectrum;
    if (!s.single_point) r.fail(c, "give the spectrum type (SPOPT,SPRS) before SOLVE");
    if (s.direction.norm() == 0.0) r.fail(c, "no excitation direction (SED) was given");
    if (s.frequencies.empty() || s.curves.empty())
      r.fail(c, "no spectrum table (FREQ and SV) was given");
    for (const auto& [damping, values] : s.curves)
      if (values.size() != s.frequencies.size())
        r.fail(c, fmt::format("the spectrum curve of damping {:g} has {} values (SV) for {} "
                              "frequencies (FREQ)",
                              damping, values.size(), s.frequencies.size()));
    a.load_steps.back().constraints = r.model.modal_load_vectors.front().constraints;
  }
  arm_creep_clock(r, r.job.steps[*r.solution.open_analysis]);
  r.solve_step(*r.solution.open_analysis);
}

void solve_expansion(DeckReader& r, const Command& c) {
  if (r.job.steps.empty() && !r.solution.seexp)
    r.fail(c,
           "expansion pass (EXPASS,ON) without a preceding analysis (or SEEXP for a "
           "superelement)");
  ExpansionPassRequest e = r.solution.expansion;
  e.superelement = r.solution.seexp;
  if (e.requests.empty()) {
    Log::info("{}:{}: SOLVE: no NUMEXP/EXPSOL given; every solution is expanded", c.where.file,
              c.where.line);
    e.requests.push_back(ExpansionRequest{0, 0.0, r.solution.last_solved_time.value_or(0.0), true});
  }
  e.where = c.where;
  Job::Step step;
  step.expansion = std::move(e);
  step.model_snapshot = std::make_shared<Model>(r.model);
  r.job.steps.push_back(std::move(step));
  r.solution.open_analysis.reset();
  r.solution.expansion.requests.clear();
  r.solve_step(r.job.steps.size() - 1);
}

void cmd_solve(DeckReader& r, const Command& c) {
  if (r.solution.expass)
    solve_expansion(r, c);
  else
    solve_current(r, c);
}

void cmd_lswrite(DeckReader& r, const Command& c) {
  const std::string l = r.label(c, 1);
  if (l == "INIT") {
    r.solution.lswrite_steps.clear();
    return;
  }
  if (l == "STAT") {
    Log::info("{}:{}: LSWRITE: {} load steps stored", c.where.file, c.where.line,
              r.solution.lswrite_steps.size());
    return;
  }
  prepare_model_for_solution(r, c);
  const int next =
      r.solution.lswrite_steps.empty() ? 1 : r.solution.lswrite_steps.rbegin()->first + 1;
  const int n = r.integer(c, 1, next);
  if (n <= 0) r.fail(c, fmt::format("load step number {} must be positive", n));
  r.solution.lswrite_steps[n] = snapshot(r, c, n);
}

void cmd_lssolve(DeckReader& r, const Command& c) {
  const auto first = r.opt_int(c, 1);
  if (!first) r.fail(c, "LSMIN missing");
  const int last = r.integer(c, 2, *first);
  const int inc = std::max(1, r.integer(c, 3, 1));
  for (long long n = *first; n <= last; n += inc) {
    auto it = r.solution.lswrite_steps.find(static_cast<int>(n));
    if (it == r.solution.lswrite_steps.end())
      r.fail(c, fmt::format("load step {} was not written (LSWRITE)", n));
    const RestartControl rescontrol = r.model.current.rescontrol;  // not a load-step option
    r.model.current = it->second;
    r.model.current.rescontrol = rescontrol;
    append_current(r, c);
  }
  // All the load steps at once: the solver knows what follows (the progress estimate covers
  // them) and solves them in order, as one SOLVE each would. RATE and TOFF are those in force
  // at LSSOLVE, for all of them.
  arm_creep_clock(r, r.job.steps[*r.solution.open_analysis]);
  r.solve_step(*r.solution.open_analysis);
}

// ---- expansion passes ---------------------------------------------------------------------------

void cmd_stress(DeckReader& r, const Command& c) {
  bool analysed = false;
  for (const auto& s : r.job.steps) analysed = analysed || s.analysis.has_value();
  if (!analysed) r.fail(c, "/STRESS without a preceding analysis (/INPUT,27)");
  const auto& last =
      *std::find_if(r.job.steps.rbegin(), r.job.steps.rend(), [](const Job::Step& s) {
         return s.analysis.has_value();
       })->analysis;
  if (last.options.method != TransientMethod::Reduced)
    r.warn(c, "/STRESS after an analysis that is not a reduced transient (KAN=5)");
  r.processor = kStress;
  r.solution.stress_requests.clear();
  r.solution.stress_count = 1;
  r.solution.stress_t_prev = 0.0;
  r.solution.stress_where = c.where;
}

void cmd_nstres(DeckReader& r, const Command& c) {
  const auto n = r.opt_int(c, 1);
  if (!n || *n <= 0) r.fail(c, "number of expanded solutions must be positive");
  r.solution.stress_count = *n;
}

void cmd_end(DeckReader& r, const Command& c) {
  if (r.solution.stress_requests.empty())
    r.fail(c, "END without an NSTRES/TIME request in the /STRESS block");
  close_stress_block(r, c.where);
}

void cmd_expass(DeckReader& r, const Command& c) {
  r.solution.expass = r.on_off(c, 1, false);
  r.solution.seexp.reset();
  r.solution.expansion = ExpansionPassRequest{};
  r.solution.expansion.static_correction = r.on_off(c, 4, true);
}

void cmd_numexp(DeckReader& r, const Command& c) {
  ExpansionRequest q;
  if (r.label(c, 1) == "ALL") {
    q.every_step = true;
    q.count = 0;
  } else {
    const auto n = r.opt_int(c, 1);
    if (!n || *n <= 0) r.fail(c, "NUM must be a positive number or ALL");
    q.count = *n;
  }
  q.t_begin = r.real(c, 2, 0.0);
  const auto end = r.opt_real(c, 3);
  if (!end && !r.solution.last_solved_time && !r.solution.seexp)
    r.fail(c, "ENDRNG missing and no solved load step with a TIME");
  // Without a solved step here (a superelement expansion), the range ends with the use pass.
  q.t_end = end                           ? *end
            : r.solution.last_solved_time ? *r.solution.last_solved_time
                                          : std::numeric_limits<double>::infinity();
  if (q.t_end < q.t_begin) r.fail(c, fmt::format("empty range {} to {}", q.t_begin, q.t_end));
  r.solution.expansion.requests.push_back(q);
}

void cmd_expsol(DeckReader& r, const Command& c) {
  const auto t = r.opt_real(c, 3);
  if (!t) r.fail(c, "only EXPSOL by time (TIMFRQ, field 3) is supported");
  r.solution.expansion.requests.push_back(ExpansionRequest{1, *t, *t, false});
}

}  // namespace

void close_stress_block(DeckReader& r, const SourceLocation& where) {
  Job::Step step;
  ExpansionPassRequest e;
  e.requests = r.solution.stress_requests;
  e.where = where;
  step.expansion = std::move(e);
  step.model_snapshot = std::make_shared<Model>(r.model);
  r.job.steps.push_back(std::move(step));
  r.solution.stress_requests.clear();
  r.solve_step(r.job.steps.size() - 1);
}

void run_frozen_analysis(DeckReader& r, const Command& c) {
  if (!r.solution.frozen) r.fail(c, "no analysis to run: AFWRITE was not issued before /INPUT,27");
  Job::Step step = *r.solution.frozen;
  step.analysis->where = c.where;
  r.job.steps.push_back(std::move(step));
  r.solution.exec_armed = false;
  r.solve_step(r.job.steps.size() - 1);
}

void register_solution_commands(std::vector<CommandSpec>& t) {
  t.push_back({"TIME", cmd_time, kPrepSolu | kStress});
  t.push_back({"DTIME", cmd_dtime, kPrepSolu});
  t.push_back({"DELTIM", cmd_dtime, kPrepSolu});
  t.push_back({"NSUBST", cmd_nsubst, kPrepSolu});
  t.push_back({"ITER", cmd_iter, kPrepSolu | kStress});
  t.push_back({"AUTOTS", cmd_autots, kPrepSolu});
  t.push_back({"KBC", cmd_kbc, kPrepSolu});
  t.push_back({"TIMINT", cmd_timint, kPrepSolu});
  t.push_back({"NLGEOM", cmd_nlgeom, kPrepSolu});
  t.push_back({"SSTIF", cmd_sstif, kPrepSolu});
  t.push_back({"RATE", cmd_rate, kPrepSolu});
  t.push_back({"TOFF", cmd_toff, kPrepSolu});
  t.push_back({"STEF", cmd_stef, kPrepSolu});
  t.push_back({"LUMPM", cmd_lumpm, kPrepSolu});
  t.push_back({"ERESX", cmd_eresx, kPrep7 | kSolu});
  t.push_back({"ANTYPE", cmd_antype, kPrepSolu});
  t.push_back({"OUTRES", cmd_outres, kPrepSolu});
  t.push_back({"OUTPR", cmd_outpr, kPrepSolu});
  t.push_back({"SEOPT", cmd_seopt, kPrepSolu});
  t.push_back({"SEEXP", cmd_seexp, kSolu});
  t.push_back({"CMSOPT", cmd_cmsopt, kPrepSolu});
  t.push_back({"LWRITE", cmd_lwrite, kPrepSolu});
  t.push_back({"AFWRITE", cmd_afwrite, kPrep7});
  t.push_back({"/EXEC", cmd_exec, kBegin | kPrep7});
  t.push_back({"SOLVE", cmd_solve, kSolu});
  t.push_back({"LSWRITE", cmd_lswrite, kPrepSolu});
  t.push_back({"LSSOLVE", cmd_lssolve, kSolu});
  t.push_back({"/STRESS", cmd_stress, kBegin | kStress});
  t.push_back({"NSTRES", cmd_nstres, kStress});
  t.push_back({"END", cmd_end, kStress});
  t.push_back({"EXPASS", cmd_expass, kSolu});
  t.push_back({"NUMEXP", cmd_numexp, kSolu});
  t.push_back({"EXPSOL", cmd_expsol, kSolu});
}

}  // namespace impactfe::deck
