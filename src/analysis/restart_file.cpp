#include "analysis/restart_file.h"

#include <fmt/format.h>

#include <filesystem>

#include "io/h5_util.h"

namespace impactfe {

namespace {

using h5::check;
using h5::Handle;

std::string point_name(int load_step, int substep) {
  return fmt::format("ls{:06d}_ss{:09d}", load_step, substep);
}

/// Names of the point groups, in name order (= load step, then substep).
std::vector<std::string> point_names(hid_t file) {
  std::vector<std::string> names;
  hsize_t idx = 0;
  H5Literate(
      file, H5_INDEX_NAME, H5_ITER_INC, &idx,
      [](hid_t, const char* name, const H5L_info_t*, void* data) -> herr_t {
        if (std::string(name).rfind("ls", 0) == 0)
          static_cast<std::vector<std::string>*>(data)->emplace_back(name);
        return 0;
      },
      &names);
  return names;
}

void write_vector(hid_t g, const std::string& name, const VectorXd& v) {
  h5::write_dataset(g, name, {static_cast<hsize_t>(v.size())}, v.data());
}
VectorXd read_vector(hid_t g, const std::string& name) {
  const std::vector<double> d = h5::read_doubles(g, name);
  return Eigen::Map<const VectorXd>(d.data(), static_cast<Eigen::Index>(d.size()));
}

/// A DOF table as rows (node, dof, value).
void write_table(hid_t g, const std::string& name, const std::map<DofKey, double>& table) {
  std::vector<double> rows;
  for (const auto& [key, value] : table)
    rows.insert(rows.end(), {static_cast<double>(key.node), static_cast<double>(key.dof), value});
  h5::write_dataset(g, name, {table.size(), 3}, rows.data());
}
std::map<DofKey, double> read_table(hid_t g, const std::string& name) {
  const std::vector<double> rows = h5::read_doubles(g, name);
  std::map<DofKey, double> table;
  for (std::size_t i = 0; i + 2 < rows.size(); i += 3)
    table[DofKey{static_cast<int>(rows[i]), static_cast<Dof>(static_cast<int>(rows[i + 1]))}] =
        rows[i + 2];
  return table;
}

void write_vec3(hid_t g, const std::string& name, const Vec3& v) {
  h5::write_dataset(g, name, {3}, v.data());
}
Vec3 read_vec3(hid_t g, const std::string& name) {
  const std::vector<double> d = h5::read_doubles(g, name);
  return Vec3(d.at(0), d.at(1), d.at(2));
}

}  // namespace

std::string restart_path(const std::string& results_path) {
  const std::string ext = ".h5";
  const bool has_ext = results_path.size() > ext.size() &&
                       results_path.compare(results_path.size() - ext.size(), ext.size(), ext) == 0;
  return (has_ext ? results_path.substr(0, results_path.size() - ext.size()) : results_path) +
         ".rst.h5";
}

void write_restart_point(const std::string& path, const RestartPoint& p,
                         bool drop_earlier_load_steps) {
  h5::silence_errors();
  try {
    Handle fapl = h5::file_access_checksummed();
    hid_t f = std::filesystem::exists(path) ? H5Fopen(path.c_str(), H5F_ACC_RDWR, fapl) : -1;
    // A new file (or one that no longer opens: a run killed while creating it) is written under
    // a temporary name and renamed into place with its first point (core/job_lock.h keeps other
    // runs of the job away from it meanwhile).
    std::string creating;
    if (f < 0) {
      creating = path + ".creating";
      Handle fcpl = h5::checksummed_group_creation_list(true);
      f = check(H5Fcreate(creating.c_str(), H5F_ACC_TRUNC, fcpl, fapl), "create " + creating);
    }
    Handle file(f);
    h5::write_attribute(file, "format", std::string("impactfe-restart"));
    const std::string name = point_name(p.load_step, p.substep);
    for (const std::string& old : point_names(file)) {
      const bool earlier = old < point_name(p.load_step, 0);
      if (old == name || (drop_earlier_load_steps && earlier))
        h5::check_status(H5Ldelete(file, old.c_str(), H5P_DEFAULT), "delete " + old);
    }
    Handle g = h5::create_group(file, name);
    h5::write_integer_attribute(g, "load_step", p.load_step);
    h5::write_integer_attribute(g, "substep", p.substep);
    h5::write_attribute(g, "time", p.time);
    h5::write_attribute(g, "t_start", p.t_start);
    h5::write_integer_attribute(g, "last", p.last ? 1 : 0);
    h5::write_integer_attribute(g, "dynamic", p.dynamic ? 1 : 0);
    h5::write_attribute(g, "h", p.h);
    h5::write_attribute(g, "last_dt", p.last_dt.value_or(-1.0));
    std::vector<int> nodes, labels;
    for (const DofKey& k : p.dofs) {
      nodes.push_back(k.node);
      labels.push_back(static_cast<int>(k.dof));
    }
    h5::write_dataset(g, "dof_nodes", {nodes.size()}, nodes.data());
    h5::write_dataset(g, "dof_labels", {labels.size()}, labels.data());
    write_vector(g, "u", p.u);
    write_vector(g, "v", p.v);
    write_vector(g, "a", p.a);
    write_vector(g, "f_ext_old", p.f_ext_old);
    write_vector(g, "f_int_old", p.f_int_old);
    write_vector(g, "f_damp_old", p.f_damp_old);
    write_vector(g, "reactions", p.reactions);
    write_vec3(g, "acel", p.acel);
    h5::write_integer_attribute(g, "n_history", static_cast<long long>(p.history.size()));
    for (std::size_t i = 0; i < p.history.size(); ++i)
      write_vector(g, fmt::format("history_{}", i), p.history[i]);
    h5::write_dataset(g, "energy", {p.energy.size()}, p.energy.data());
    h5::write_dataset(g, "status_ids", {p.status_ids.size()}, p.status_ids.data());
    h5::write_dataset(g, "status_codes", {p.status_codes.size()}, p.status_codes.data());
    // Committed element states: ids, offsets (n + 1) into one array of values.
    std::vector<int> state_ids;
    std::vector<long long> offsets{0};
    std::vector<double> values;
    for (const auto& [id, state] : p.element_states) {
      state_ids.push_back(id);
      values.insert(values.end(), state.begin(), state.end());
      offsets.push_back(static_cast<long long>(values.size()));
    }
    std::vector<double> offsets_d(offsets.begin(), offsets.end());
    h5::write_dataset(g, "element_state_ids", {state_ids.size()}, state_ids.data());
    h5::write_dataset(g, "element_state_offsets", {offsets_d.size()}, offsets_d.data());
    h5::write_dataset(g, "element_state_values", {values.size()}, values.data());
    // The AUTOTS step controller of a point inside an AUTOTS load step.
    h5::write_integer_attribute(g, "autots", p.autots ? 1 : 0);
    if (p.autots) {
      const StepController::State& s = *p.autots;
      const std::vector<double> a{s.time,
                                  s.dt,
                                  s.ceiling ? 1.0 : 0.0,
                                  s.ceiling.value_or(0.0),
                                  static_cast<double>(s.easy),
                                  s.done ? 1.0 : 0.0,
                                  p.autots_t_end};
      h5::write_dataset(g, "autots_state", {a.size()}, a.data());
    }
    write_table(g, "step_forces", p.step_forces);
    write_table(g, "step_constraints", p.step_constraints);
    write_vec3(g, "step_acel", p.step_acel);
    h5::write_integer_attribute(g, "has_previous", p.has_previous ? 1 : 0);
    write_table(g, "previous_forces", p.previous_forces);
    write_table(g, "previous_constraints", p.previous_constraints);
    write_vec3(g, "previous_acel", p.previous_acel);
    h5::check_status(H5Fflush(file, H5F_SCOPE_GLOBAL), "flush " + path);
    if (!creating.empty()) {
      g.reset();
      file.reset();
      std::error_code ec;
      std::filesystem::rename(creating, path, ec);
      if (ec) throw std::runtime_error("cannot rename " + creating + ": " + ec.message());
    }
  } catch (const std::runtime_error& e) {
    throw SolutionError(fmt::format("restart file '{}': {}", path, e.what()));
  }
}

RestartPoint read_restart_point(const std::string& path, std::optional<int> load_step,
                                std::optional<int> substep, const SourceLocation& where) {
  h5::silence_errors();
  if (!std::filesystem::exists(path))
    throw InputError(where, fmt::format("no restart file '{}' (the run to continue keeps its "
                                        "restart points there when RESCONTROL asks for them)",
                                        path));
  Handle fapl = h5::file_access_checksummed();
  const hid_t f = H5Fopen(path.c_str(), H5F_ACC_RDONLY, fapl);
  if (f < 0) throw InputError(where, fmt::format("cannot open restart file '{}'", path));
  Handle file(f);
  const std::vector<std::string> names = point_names(file);
  std::string chosen;
  for (const std::string& n : names) {
    const int ls = std::stoi(n.substr(2, 6));
    const int ss = std::stoi(n.substr(12));
    if ((!load_step || ls == *load_step) && (!substep || ss == *substep)) chosen = n;
  }
  if (chosen.empty()) {
    std::string list;
    for (const std::string& n : names)
      list += fmt::format("{}{},{}", list.empty() ? "" : "; ", std::stoi(n.substr(2, 6)),
                          std::stoi(n.substr(12)));
    throw InputError(where, fmt::format("no restart point at load step {}, substep {} in '{}' "
                                        "(points there, as LDSTEP,SUBSTEP: {})",
                                        load_step ? std::to_string(*load_step) : "(last)",
                                        substep ? std::to_string(*substep) : "(last)", path,
                                        list.empty() ? "none" : list));
  }
  try {
    Handle g = h5::open_group(file, chosen);
    RestartPoint p;
    p.load_step = static_cast<int>(h5::read_double_attribute(g, "load_step"));
    p.substep = static_cast<int>(h5::read_double_attribute(g, "substep"));
    p.time = h5::read_double_attribute(g, "time");
    p.t_start = h5::read_double_attribute(g, "t_start");
    p.last = h5::read_double_attribute(g, "last") != 0.0;
    p.dynamic = h5::read_double_attribute(g, "dynamic") != 0.0;
    p.h = h5::read_double_attribute(g, "h");
    const double last_dt = h5::read_double_attribute(g, "last_dt");
    if (last_dt > 0.0) p.last_dt = last_dt;
    const std::vector<int> nodes = h5::read_ints(g, "dof_nodes");
    const std::vector<int> labels = h5::read_ints(g, "dof_labels");
    for (std::size_t i = 0; i < nodes.size(); ++i)
      p.dofs.push_back(DofKey{nodes[i], static_cast<Dof>(labels.at(i))});
    p.u = read_vector(g, "u");
    p.v = read_vector(g, "v");
    p.a = read_vector(g, "a");
    p.f_ext_old = read_vector(g, "f_ext_old");
    p.f_int_old = read_vector(g, "f_int_old");
    p.f_damp_old = read_vector(g, "f_damp_old");
    p.reactions = read_vector(g, "reactions");
    p.acel = read_vec3(g, "acel");
    const int n_history = static_cast<int>(h5::read_double_attribute(g, "n_history"));
    for (int i = 0; i < n_history; ++i)
      p.history.push_back(read_vector(g, fmt::format("history_{}", i)));
    p.energy = h5::read_doubles(g, "energy");
    p.status_ids = h5::read_ints(g, "status_ids");
    p.status_codes = h5::read_ints(g, "status_codes");
    const std::vector<int> state_ids = h5::read_ints(g, "element_state_ids");
    const std::vector<double> offsets = h5::read_doubles(g, "element_state_offsets");
    const std::vector<double> values = h5::read_doubles(g, "element_state_values");
    if (offsets.size() != state_ids.size() + 1)
      throw std::runtime_error("element states: offsets do not match the ids");
    for (std::size_t i = 0; i < state_ids.size(); ++i) {
      const auto begin = static_cast<std::size_t>(offsets[i]);
      const auto end = static_cast<std::size_t>(offsets[i + 1]);
      if (begin > end || end > values.size())
        throw std::runtime_error("element states: offsets out of range");
      p.element_states[state_ids[i]].assign(values.begin() + static_cast<std::ptrdiff_t>(begin),
                                            values.begin() + static_cast<std::ptrdiff_t>(end));
    }
    if (h5::read_double_attribute(g, "autots") != 0.0) {
      const std::vector<double> a = h5::read_doubles(g, "autots_state");
      if (a.size() != 7) throw std::runtime_error("autots_state: 7 values expected");
      StepController::State s;
      s.time = a[0];
      s.dt = a[1];
      if (a[2] != 0.0) s.ceiling = a[3];
      s.easy = static_cast<int>(a[4]);
      s.done = a[5] != 0.0;
      p.autots = s;
      p.autots_t_end = a[6];
    }
    p.step_forces = read_table(g, "step_forces");
    p.step_constraints = read_table(g, "step_constraints");
    p.step_acel = read_vec3(g, "step_acel");
    p.has_previous = h5::read_double_attribute(g, "has_previous") != 0.0;
    p.previous_forces = read_table(g, "previous_forces");
    p.previous_constraints = read_table(g, "previous_constraints");
    p.previous_acel = read_vec3(g, "previous_acel");
    return p;
  } catch (const std::runtime_error& e) {
    throw InputError(where, fmt::format("restart file '{}', point {}: {}", path, chosen, e.what()));
  }
}

}  // namespace impactfe
