// /CLEAR, SAVE, RESUME, PARSAV, PARRES and RESCONTROL (APDL_SCRIPTING §A.15, APDL_MODELING
// §9.5). SAVE writes
// the database to a JSON file `<Fname>.<Ext>` (default `<jobname>.db`) in the working
// directory; the geometry part reuses the
// superelement file's model text (io/superelement_file.h), the rest is described in
// docs/deck_reader.md ("Database file").
#include <fmt/format.h>

#include <filesystem>
#include <fstream>
#include <nlohmann/json.hpp>

#include "core/files.h"
#include "deck/deck_context.h"
#include "io/superelement_file.h"

namespace impactfe::deck {

using json = nlohmann::json;

void DeckReader::clear_database(const Command& c) {
  if (options.host != nullptr) options.host->clear(job);
  std::vector<std::string> ignored = std::move(job.ignored_commands);
  const std::string jobname = model.jobname;  // /CLEAR keeps the jobname (/FILNAME changes it)
  job = Job{};
  job.ignored_commands = std::move(ignored);
  model.dialect = dialect;
  model.jobname = jobname;
  model.options.integrator =
      dialect == Dialect::Classic4x ? IntegratorKind::Houbolt : IntegratorKind::Newmark;
  processor = kBegin;
  params.clear();
  output.to_terminal();
  scripting.increments.clear();  // *CREATE files and *BEGIN blocks survive
  if (scripting.command_file.stream.is_open()) scripting.command_file.stream.close();
  scripting.command_file.path.clear();
  scripting.vector_settings = VectorSettings{};
  modeling = ModelingState::initial(dialect);
  solution = SolutionState{};
  last_command_.reset();
  post.reset();  // POST1 set, element table, POST26 variables
  Log::info("{}:{}: /CLEAR: database cleared (a new job begins)", c.where.file, c.where.line);
}

namespace {

void cmd_clear(DeckReader& r, const Command& c) {
  const std::string read = r.label(c, 1);
  if (!read.empty() && read != "START" && read != "NOSTART")
    r.fail(c, fmt::format("Read '{}': START or NOSTART", read));
  r.clear_database(c);
}

std::string database_path(DeckReader& r, const Command& c) {
  std::string name = r.text_field(c, 1);
  std::string ext = r.text_field(c, 2);
  if (name.empty()) name = r.model.jobname;
  if (ext.empty()) ext = "db";
  return name + "." + ext;
}

json opt(const std::optional<double>& v) {
  return v ? json(*v) : json(nullptr);
}
std::optional<double> opt_of(const json& j) {
  return j.is_null() ? std::nullopt : std::optional<double>(j.get<double>());
}

json options_json(const AnalysisOptions& o) {
  json m = json::object();
  for (const auto& [mode, ratio] : o.modal_damping) m[std::to_string(mode)] = ratio;
  return {{"type", static_cast<int>(o.type)},
          {"method", static_cast<int>(o.method)},
          {"integrator", static_cast<int>(o.integrator)},
          {"tintp",
           {opt(o.tintp.gamma), opt(o.tintp.alpha), opt(o.tintp.delta), opt(o.tintp.alpha_f),
            opt(o.tintp.alpha_m)}},
          {"large_deflection", o.large_deflection},
          {"stress_stiffening", o.stress_stiffening},
          {"lumped_mass", o.lumped_mass},
          {"eresx", static_cast<int>(o.nodal_stresses)},
          {"convergence",
           {o.convergence.max_iterations, o.convergence.force_tolerance, o.convergence.force_minref,
            opt(o.convergence.displacement_tolerance), o.convergence.full_newton,
            o.convergence.line_search, o.convergence.line_search_auto}},
          {"modal",
           {o.modal.n_modes, opt(o.modal.freq_begin), opt(o.modal.freq_end),
            o.modal.normalize_to_unity, o.modal.method}},
          {"msup_modes", o.msup_modes},
          {"damping_ratio", o.damping_ratio},
          {"modal_damping", m},
          {"alpha_damping", o.alpha_damping},
          {"beta_damping", o.beta_damping},
          {"superelement_matrices", o.superelement_matrices},
          {"superelement_name", o.superelement_name},
          {"total_masters", o.total_masters ? json(*o.total_masters) : json(nullptr)},
          {"total_masters_exclude_rotations", o.total_masters_exclude_rotations},
          {"kay", o.kay}};
}

AnalysisOptions options_of(const json& j) {
  AnalysisOptions o;
  o.type = static_cast<AnalysisType>(j.at("type").get<int>());
  o.method = static_cast<TransientMethod>(j.at("method").get<int>());
  o.integrator = static_cast<IntegratorKind>(j.at("integrator").get<int>());
  const json& t = j.at("tintp");
  o.tintp = {opt_of(t[0]), opt_of(t[1]), opt_of(t[2]), opt_of(t[3]), opt_of(t[4])};
  o.large_deflection = j.at("large_deflection");
  o.stress_stiffening = j.at("stress_stiffening");
  o.lumped_mass = j.at("lumped_mass");
  o.nodal_stresses = static_cast<NodalStressRule>(j.value("eresx", 0));  // older files: DEFA
  const json& cv = j.at("convergence");
  o.convergence = {cv[0],
                   cv[1],
                   cv[2],
                   opt_of(cv[3]),
                   cv[4],
                   cv.size() > 5 && cv[5].get<bool>(),
                   cv.size() > 6 && cv[6].get<bool>()};
  const json& md = j.at("modal");
  o.modal = {md[0], opt_of(md[1]), opt_of(md[2]), md[3], md[4]};
  o.msup_modes = j.at("msup_modes");
  o.damping_ratio = j.at("damping_ratio");
  for (const auto& [mode, ratio] : j.at("modal_damping").items())
    o.modal_damping[std::stoi(mode)] = ratio.get<double>();
  o.alpha_damping = j.at("alpha_damping");
  o.beta_damping = j.at("beta_damping");
  o.superelement_matrices = j.at("superelement_matrices");
  o.superelement_name = j.at("superelement_name");
  if (!j.at("total_masters").is_null()) o.total_masters = j.at("total_masters").get<int>();
  o.total_masters_exclude_rotations = j.at("total_masters_exclude_rotations");
  o.kay = j.at("kay").get<std::map<std::string, int>>();
  return o;
}

json dof_table(const std::map<DofKey, double>& m) {
  json a = json::array();
  for (const auto& [k, v] : m) a.push_back({k.node, static_cast<int>(k.dof), v});
  return a;
}
std::map<DofKey, double> dof_table_of(const json& a) {
  std::map<DofKey, double> m;
  for (const auto& e : a) m[DofKey{e[0], static_cast<Dof>(e[1].get<int>())}] = e[2];
  return m;
}

/// OUTRES per-item specifications: per item a list of [every, component, ids].
json output_items_json(const OutputControl& f) {
  json items = json::array();
  for (const auto& specs : f.items) {
    json list = json::array();
    for (const auto& spec : specs) list.push_back({spec.every, spec.component, spec.ids});
    items.push_back(list);
  }
  return items;
}

void output_items_of(const json& j, OutputControl& f) {
  for (std::size_t i = 0; i < f.items.size() && i < j.size(); ++i)
    for (const auto& spec : j[i])
      f.items[i].push_back(OutputSpec{spec[0].get<int>(), spec[1].get<std::string>(),
                                      spec[2].get<std::vector<int>>()});
}

json opt_int(const std::optional<int>& v) {
  return v ? json(*v) : json(nullptr);
}
std::optional<int> opt_int_of(const json& j) {
  return j.is_null() ? std::nullopt : std::optional<int>(j.get<int>());
}

/// AUTOTS, the DELTIM / NSUBST limits (StepControl) and RESCONTROL of the current load state.
json step_control_json(const LoadStep& s) {
  const StepControl& c = s.control;
  const RestartControl& rc = s.rescontrol;
  return {{"autots", c.automatic ? json(*c.automatic) : json(nullptr)},
          {"dt_min", opt(c.dt_min)},
          {"dt_max", opt(c.dt_max)},
          {"n_max", opt_int(c.n_max)},
          {"n_min", opt_int(c.n_min)},
          {"carry", c.carry},
          {"rescontrol", {rc.defined, rc.load_steps, rc.frequency}}};
}
void step_control_of(const json& j, LoadStep& s) {
  StepControl& c = s.control;
  if (!j.at("autots").is_null()) c.automatic = j.at("autots").get<bool>();
  c.dt_min = opt_of(j.at("dt_min"));
  c.dt_max = opt_of(j.at("dt_max"));
  c.n_max = opt_int_of(j.at("n_max"));
  c.n_min = opt_int_of(j.at("n_min"));
  c.carry = j.at("carry");
  const json& rc = j.at("rescontrol");
  s.rescontrol = {rc[0].get<bool>(), rc[1].get<int>(), rc[2].get<int>()};
}

json temperature_table(const std::map<int, double>& t) {
  json out = json::array();
  for (const auto& [node, value] : t) out.push_back({node, value});
  return out;
}

json load_state_json(const LoadStep& s) {
  const RotationalLoads& w = s.rotation;
  json rotation = json::array();
  for (const Vec3* v : {&w.omega, &w.domega, &w.cg_location, &w.cg_omega, &w.cg_domega})
    rotation.push_back({(*v)(0), (*v)(1), (*v)(2)});
  return {{"time_end", opt(s.time_end)},
          {"rotation", rotation},
          {"dt", opt(s.dt)},
          {"n_substeps", s.n_substeps ? json(*s.n_substeps) : json(nullptr)},
          {"output_every", s.output.every},
          {"output_items", output_items_json(s.output)},
          {"stepped", s.stepped},
          {"reformulation", s.reformulation},
          {"time_integration", s.time_integration},
          {"acel", {s.acel(0), s.acel(1), s.acel(2)}},
          {"constraints", dof_table(s.constraints)},
          {"forces", dof_table(s.forces)},
          {"step_control", step_control_json(s)},
          {"reference_temperature", s.reference_temperature},
          {"uniform_temperature", opt(s.uniform_temperature)},
          {"node_temperatures", temperature_table(s.node_temperatures)}};
}

LoadStep load_state_of(const json& j) {
  LoadStep s;
  s.time_end = opt_of(j.at("time_end"));
  s.dt = opt_of(j.at("dt"));
  if (!j.at("n_substeps").is_null()) s.n_substeps = j.at("n_substeps").get<int>();
  s.output.every = j.at("output_every");
  if (j.contains("output_items")) output_items_of(j.at("output_items"), s.output);
  s.stepped = j.at("stepped");
  s.reformulation = j.at("reformulation");
  s.time_integration = j.at("time_integration");
  s.acel = Vec3(j.at("acel")[0], j.at("acel")[1], j.at("acel")[2]);
  if (j.contains("rotation")) {  // older files: none
    RotationalLoads& w = s.rotation;
    Vec3* v[] = {&w.omega, &w.domega, &w.cg_location, &w.cg_omega, &w.cg_domega};
    for (std::size_t k = 0; k < 5; ++k) {
      const json& e = j.at("rotation").at(k);
      *v[k] = Vec3(e[0], e[1], e[2]);
    }
  }
  s.constraints = dof_table_of(j.at("constraints"));
  s.forces = dof_table_of(j.at("forces"));
  if (j.contains("step_control")) step_control_of(j.at("step_control"), s);  // older files: none
  s.reference_temperature = j.value("reference_temperature", 0.0);
  if (j.contains("uniform_temperature"))
    s.uniform_temperature = opt_of(j.at("uniform_temperature"));
  if (j.contains("node_temperatures"))
    for (const auto& e : j.at("node_temperatures")) s.node_temperatures[e[0]] = e[1];
  return s;
}

json param_json(const Param& p) {
  json j = {{"type", param_type_name(p.type)}};
  switch (p.type) {
    case ParamType::Number:
      j["value"] = p.number;
      break;
    case ParamType::Text:
      j["value"] = p.text;
      break;
    case ParamType::CharArray:
    case ParamType::StringArray:
      j["dims"] = {p.imax, p.jmax, p.kmax};
      j["values"] = p.texts;
      break;
    default:
      j["dims"] = {p.imax, p.jmax, p.kmax};
      j["values"] = p.values;
      j["variables"] = p.variables;
  }
  return j;
}

Param param_of(const json& j) {
  const std::string type = j.at("type");
  if (type == "SCALAR") return Param::scalar(j.at("value"));
  if (type == "CHARACTER") return Param::character(j.at("value"));
  const json& d = j.at("dims");
  const ParamType t = type == "CHAR"     ? ParamType::CharArray
                      : type == "STRING" ? ParamType::StringArray
                      : type == "TABLE"  ? ParamType::Table
                                         : ParamType::Array;
  Param p = Param::array(t, d[0], d[1], d[2]);
  if (p.is_character_array()) {
    const std::size_t size = p.texts.size();
    p.texts = j.at("values").get<std::vector<std::string>>();
    if (p.texts.size() != size) throw std::runtime_error("array size mismatch");
  } else {
    const auto values = j.at("values").get<std::vector<double>>();
    if (values.size() != p.values.size()) throw std::runtime_error("array size mismatch");
    p.values = values;
    p.variables = j.at("variables").get<std::array<std::string, 3>>();
  }
  return p;
}

void cmd_save(DeckReader& r, const Command& c) {
  // SAVE,Fname,Ext,--,Slab: ALL (default) or MODEL.
  const std::string slab = r.label(c, 4);
  if (!slab.empty() && slab != "ALL" && slab != "MODEL")
    r.fail(c, fmt::format("Slab '{}' is not supported (ALL or MODEL)", slab));
  const Model& m = r.model;
  json j;
  j["format"] = "impactfe-db";
  j["version"] = 1;
  j["slab"] = slab.empty() ? "ALL" : slab;
  j["jobname"] = m.jobname;
  j["title"] = m.title;
  j["units"] = m.units;
  j["geometry"] = serialize_generation_model(m, false, false);
  json se = json::object();
  for (const auto& [id, e] : m.elements)
    if (!e.superelement_file.empty()) se[std::to_string(id)] = e.superelement_file;
  j["superelement_files"] = se;
  j["attributes"] = {r.modeling.current_type, r.modeling.current_real, r.modeling.current_mat,
                     r.modeling.current_secnum, r.modeling.secnum_given};
  json masters = json::array();
  for (const auto& k : m.masters) masters.push_back({k.node, static_cast<int>(k.dof)});
  j["masters"] = masters;
  json gaps = json::array();
  for (const auto& g : m.gap_conditions)
    gaps.push_back({g.node_i, g.node_j, static_cast<int>(g.dof), g.stiffness, g.gap, g.damping});
  j["gaps"] = gaps;
  json coupled = json::array();
  for (const auto& [id, set] : m.coupled_sets)
    coupled.push_back({id, static_cast<int>(set.dof), set.nodes});
  j["coupled_sets"] = coupled;
  // Constraint equations [id, constant, [[node, dof, c], ...]] and rigid regions
  // [master, slaves, translations, rotations, only].
  json equations = json::array();
  for (const auto& [id, eq] : m.constraint_equations) {
    json terms = json::array();
    for (const auto& t : eq.terms)
      terms.push_back({t.dof.node, static_cast<int>(t.dof.dof), t.coefficient});
    equations.push_back({id, eq.constant, terms});
  }
  j["constraint_equations"] = equations;
  json regions = json::array();
  for (const auto& region : m.rigid_regions) {
    std::vector<int> only;
    for (Dof d : region.only) only.push_back(static_cast<int>(d));
    regions.push_back({region.master, region.slaves, region.translations, region.rotations, only});
  }
  j["rigid_regions"] = regions;
  if (j["slab"] == "ALL") {
    json ic = json::array();
    for (const auto& [k, v] : m.initial_conditions)
      ic.push_back({k.node, static_cast<int>(k.dof), v.displacement, v.velocity});
    j["initial_conditions"] = ic;
    j["options"] = options_json(m.options);
    j["loads"] = load_state_json(m.current);
  }
  json params = json::object();
  for (const auto& [name, p] : r.params.all()) params[name] = param_json(p);
  j["parameters"] = params;
  // JSON strings are UTF-8: a title or string parameter with other bytes (Latin-1 text, or
  // garbage) is written with U+FFFD in their place rather than refused.
  const std::string text = j.dump(1, ' ', false, json::error_handler_t::replace);
  r.count_work(c, DeckReader::database_work(text.size()));
  const std::string path = database_path(r, c);
  std::ofstream out(path);
  if (!out) r.fail(c, fmt::format("cannot write '{}'", path));
  out << text << '\n';
  Log::info("{}:{}: SAVE: database written to {}", c.where.file, c.where.line, path);
}

void cmd_resume(DeckReader& r, const Command& c) {
  // RESUME,Fname,Ext,--,NOPAR,KNOPLOT: NOPAR 1 keeps the current parameters.
  const std::string path = database_path(r, c);
  std::optional<std::string> in;
  try {
    in = read_file(path, ReadLimits::bytes());  // rank 0's disk under MPI (core/files.h)
  } catch (const OversizedFileError& e) {
    r.fail(c, e.what());
  }
  if (!in) r.fail(c, fmt::format("no database file '{}' (SAVE writes it)", path));
  r.count_work(c, DeckReader::database_work(in->size()));
  const bool keep_params = r.integer(c, 4, 0) == 1;
  try {
    const json j = json::parse(*in);
    if (j.at("format") != "impactfe-db" || j.at("version").get<int>() != 1)
      r.fail(c, fmt::format("'{}' is not an impactfe database (version 1)", path));
    bool lumped = false, sstif = false;
    Model loaded = deserialize_generation_model(j.at("geometry").get<std::string>(), lumped, sstif);
    Model& m = r.model;
    m.nodes = std::move(loaded.nodes);
    m.element_types = std::move(loaded.element_types);
    m.real_sets = std::move(loaded.real_sets);
    m.materials = std::move(loaded.materials);
    m.sections = std::move(loaded.sections);
    m.elements = std::move(loaded.elements);
    for (auto& [id, e] : m.elements) e.where = c.where;
    for (const auto& [id, file] : j.at("superelement_files").items())
      m.elements.at(std::stoi(id)).superelement_file = file.get<std::string>();
    for (auto& [id, t] : m.element_types) t.where = c.where;
    m.title = j.at("title");
    m.units = j.value("units", std::string());
    const json& a = j.at("attributes");
    r.modeling.current_type = a[0];
    r.modeling.current_real = a[1];
    r.modeling.current_mat = a[2];
    r.modeling.current_secnum = a[3];
    r.modeling.secnum_given = a[4];
    m.masters.clear();
    for (const auto& k : j.at("masters"))
      m.masters.push_back({k[0], static_cast<Dof>(k[1].get<int>())});
    m.gap_conditions.clear();
    for (const auto& g : j.at("gaps")) {
      GapCondition gc{g[0], g[1], static_cast<Dof>(g[2].get<int>()), g[3], g[4], g[5], c.where};
      m.gap_conditions.push_back(gc);
    }
    m.coupled_sets.clear();
    if (j.contains("coupled_sets"))  // older files: none
      for (const auto& e : j.at("coupled_sets")) {
        CoupledSet set{e[0], static_cast<Dof>(e[1].get<int>()), e[2].get<std::vector<int>>(),
                       c.where};
        m.coupled_sets[set.id] = set;
      }
    m.constraint_equations.clear();
    if (j.contains("constraint_equations"))  // older files: none
      for (const auto& e : j.at("constraint_equations")) {
        ConstraintEquation eq;
        eq.id = e[0];
        eq.constant = e[1];
        eq.where = c.where;
        for (const auto& t : e[2])
          eq.terms.push_back({DofKey{t[0], static_cast<Dof>(t[1].get<int>())}, t[2]});
        m.constraint_equations[eq.id] = eq;
      }
    m.rigid_regions.clear();
    if (j.contains("rigid_regions"))
      for (const auto& e : j.at("rigid_regions")) {
        RigidRegion region;
        region.master = e[0];
        region.slaves = e[1].get<std::vector<int>>();
        region.translations = e[2];
        region.rotations = e[3];
        for (int d : e[4].get<std::vector<int>>()) region.only.push_back(static_cast<Dof>(d));
        region.where = c.where;
        m.rigid_regions.push_back(region);
      }
    if (j.at("slab") == "ALL") {
      m.initial_conditions.clear();
      for (const auto& e : j.at("initial_conditions"))
        m.initial_conditions[DofKey{e[0], static_cast<Dof>(e[1].get<int>())}] = {e[2], e[3]};
      m.options = options_of(j.at("options"));
      m.current = load_state_of(j.at("loads"));
    }
    r.modeling.element_order.clear();
    for (const auto& [id, e] : m.elements) r.modeling.element_order.push_back(id);
    r.model.selection
        .select_everything();  // the database file holds no selection: everything is selected
    if (!keep_params) {
      const bool degrees = r.params.degrees;
      r.params.clear();
      r.params.degrees = degrees;
      for (const auto& [name, p] : j.at("parameters").items()) r.params.define(name, param_of(p));
    }
  } catch (const InputError&) {
    throw;
  } catch (const std::exception& e) {
    r.fail(c, fmt::format("'{}' is damaged: {}", path, e.what()));
  }
  Log::info("{}:{}: RESUME: database read from {}", c.where.file, c.where.line, path);
}

/// PARSAV / PARRES file: Fname (default jobname) and Ext (default PARM when Fname is blank, none
/// when Fname is given alone), as MAPDL names it.
std::string parameter_file_path(DeckReader& r, const Command& c) {
  const std::string name = r.text_field(c, 2);
  const std::string ext = r.text_field(c, 3);
  if (name.empty()) return r.model.jobname + "." + (ext.empty() ? "parm" : ext);
  return ext.empty() ? name : name + "." + ext;
}

void cmd_parsav(DeckReader& r, const Command& c) {
  // PARSAV,Lab,Fname,Ext: SCALAR (default) the scalar parameters, ALL the arrays too (MAPDL).
  const std::string lab = c.blank(1) ? "SCALAR" : r.label(c, 1);
  if (lab != "SCALAR" && lab != "ALL") r.fail(c, fmt::format("Lab '{}': SCALAR or ALL", c.text(1)));
  json params = json::object();
  for (const auto& [name, p] : r.params.all())
    if (lab == "ALL" || !p.is_array()) params[name] = param_json(p);
  const json j = {{"format", "impactfe-parameters"}, {"version", 1}, {"parameters", params}};
  const std::string text = j.dump(1, ' ', false, json::error_handler_t::replace);
  r.count_work(c, DeckReader::database_work(text.size()));
  const std::string path = parameter_file_path(r, c);
  std::ofstream out(path);
  if (!out) r.fail(c, fmt::format("cannot write '{}'", path));
  out << text << '\n';
  Log::info("{}:{}: PARSAV: {} parameters written to {}", c.where.file, c.where.line, params.size(),
            path);
}

void cmd_parres(DeckReader& r, const Command& c) {
  // PARRES,Lab,Fname,Ext: NEW (default) replaces the parameters by the file's, CHANGE adds them,
  // replacing those of the same name (MAPDL).
  const std::string lab = c.blank(1) ? "NEW" : r.label(c, 1);
  if (lab != "NEW" && lab != "CHANGE") r.fail(c, fmt::format("Lab '{}': NEW or CHANGE", c.text(1)));
  const std::string path = parameter_file_path(r, c);
  const auto in = read_file(path);
  if (!in) r.fail(c, fmt::format("no parameter file '{}' (PARSAV writes it)", path));
  r.count_work(c, DeckReader::database_work(in->size()));
  try {
    const json j = json::parse(*in);
    if (j.at("format") != "impactfe-parameters" || j.at("version").get<int>() != 1)
      r.fail(c, fmt::format("'{}' is not an impactfe parameter file (version 1)", path));
    if (lab == "NEW") {
      const bool degrees = r.params.degrees;
      r.params.clear();
      r.params.degrees = degrees;
    }
    for (const auto& [name, p] : j.at("parameters").items()) r.params.define(name, param_of(p));
  } catch (const InputError&) {
    throw;
  } catch (const std::exception& e) {
    r.fail(c, fmt::format("'{}' is damaged: {}", path, e.what()));
  }
}

/// RESCONTROL,Action,Ldstep,Frequency (APDL_MODELING §9.5): DEFINE (default) sets the load
/// steps (ALL, LAST, N, NONE) and substeps (LAST, N, NONE) that keep a restart point; NONE as
/// Ldstep turns restart files off; STATUS / FILE_SUMMARY print; NORESTART / LINEAR are noted.
void cmd_rescontrol(DeckReader& r, const Command& c) {
  const std::string action = r.label(c, 1);
  RestartControl& rc = r.model.current.rescontrol;
  if (action == "STATUS" || action == "FILE_SUMMARY" || action == "FILE") {
    Log::info("{}:{}: RESCONTROL: restart points at load steps {} and substeps {}", c.where.file,
              c.where.line,
              rc.load_steps < 0    ? "NONE"
              : rc.load_steps == 0 ? "LAST"
                                   : fmt::format("every {}", rc.load_steps),
              rc.frequency < 0    ? "NONE"
              : rc.frequency == 0 ? "LAST"
                                  : fmt::format("every {}", rc.frequency));
    return;
  }
  if (action == "NORESTART") {
    rc.defined = false;
    return;
  }
  if (action == "LINEAR") {
    r.warn(c, "RESCONTROL,LINEAR ignored (restart points are kept for linear runs alike)");
    return;
  }
  if (!action.empty() && action != "DEFINE")
    r.fail(c, fmt::format("bad action '{}' (DEFINE, NONE, STATUS, FILE_SUMMARY, NORESTART)",
                          c.text(1)));
  rc.defined = true;
  const std::string ls = r.label(c, 2);
  if (ls == "ALL")
    rc.load_steps = 1;
  else if (ls == "LAST" || ls.empty())
    rc.load_steps = 0;
  else if (ls == "NONE")
    rc.load_steps = -1;
  else {
    const int n = r.integer(c, 2, 0);
    if (n == 0) r.fail(c, fmt::format("bad Ldstep '{}' (ALL, LAST, NONE, N)", c.text(2)));
    rc.load_steps = std::abs(n);  // -N: every N-th load step, as N
  }
  const std::string f = r.label(c, 3);
  if (f == "LAST" || f.empty())
    rc.frequency = 0;
  else if (f == "NONE")
    rc.frequency = -1;
  else if (f == "ALL")
    rc.frequency = 1;
  else {
    const int n = r.integer(c, 3, 0);
    if (n <= 0)
      r.fail(c, fmt::format("Frequency '{}' not supported (LAST, NONE, N > 0)", c.text(3)));
    rc.frequency = n;
  }
  if (!c.blank(4) && r.integer(c, 4, -1) != -1)
    r.warn(c, "MAXFILES ignored: every requested restart point is kept in <jobname>.rst.h5");
}

}  // namespace

void register_database_commands(std::vector<CommandSpec>& t) {
  t.push_back({"/CLEAR", cmd_clear, kAnywhere});
  t.push_back({"SAVE", cmd_save, kAnywhere});
  // RESUME is valid in any processor (MAPDL RESUME): the VM decks RESUME in POST26 to bring
  // back the parameters a SAVE kept before a /CLEAR.
  t.push_back({"RESUME", cmd_resume, kAnywhere});
  t.push_back({"RESCONTROL", cmd_rescontrol, kPrepSolu});
  t.push_back({"PARSAV", cmd_parsav, kAnywhere});
  t.push_back({"PARRES", cmd_parres, kAnywhere});
}

}  // namespace impactfe::deck
