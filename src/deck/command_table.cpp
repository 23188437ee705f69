// The single command table: every handler group registers its commands here once.
#include <algorithm>
#include <unordered_map>

#include "deck/deck_context.h"

namespace impactfe::deck {

const char* processor_name(unsigned processor) {
  switch (processor) {
    case kBegin:
      return "Begin level";
    case kPrep7:
      return "/PREP7";
    case kSolu:
      return "/SOLU";
    case kPost1:
      return "/POST1";
    case kPost26:
      return "/POST26";
    case kStress:
      return "/STRESS";
    default:
      return "?";
  }
}

namespace {

struct Tables {
  std::vector<CommandSpec> commands;
  std::vector<CommandGroup> groups;
};

const Tables& tables() {
  static const Tables tables = [] {
    Tables t;
    const auto add = [&t](void (*reg)(std::vector<CommandSpec>&), const char* title,
                          const char* doc) {
      const std::size_t begin = t.commands.size();
      reg(t.commands);
      t.groups.push_back({title, doc, begin, t.commands.size()});
    };
    const char* kDeck = "docs/deck_reader.md";
    const char* kPost = "docs/post_processing.md";
    add(register_session_commands, "Session, processors and control commands", kDeck);
    add(register_prep7_commands,
        "Element types, sections, nodes, elements, master DOFs, 4x analysis keys", kDeck);
    add(register_generation_commands, "Generation (copies, fills, reflections)", kDeck);
    add(register_solution_commands, "Analysis settings and SOLVE", "docs/solution_control.md");
    add(register_convergence_commands, "Equilibrium iterations (Newton, line search, criteria)",
        "docs/solution_control.md");
    add(register_dynamics_commands,
        "Dynamic analysis options (method, integration, damping, modes)",
        "docs/time_integration.md");
    add(register_spectrum_commands,
        "Response spectrum analysis (spectrum, direction, mode combination)",
        "docs/spectrum_analysis.md");
    add(register_load_commands, "Constraints, forces and initial conditions", kDeck);
    add(register_thermal_coupling_commands, "Temperatures and coupled DOF sets",
        "docs/thermal_loads.md");
    add(register_constraint_equation_commands, "Constraint equations and rigid regions",
        "docs/constraints.md");
    add(register_component_commands, "Components", kDeck);
    add(register_get_commands, "*GET", kDeck);
    add(register_post1_commands, "POST1", kPost);
    add(register_post1_plot_commands, "POST1 pictures", kPost);
    add(register_post26_commands, "POST26", kPost);
    add(register_csys_commands, "Coordinate systems and working plane", "docs/modeling.md");
    add(register_solid_model_commands, "Solid model: keypoints, lines, areas, volumes",
        "docs/modeling.md");
    add(register_solid_edit_commands, "Solid model editing", "docs/modeling.md");
    add(register_mesh_commands, "Meshing", "docs/modeling.md");
    add(register_contact_commands, "Contact pairs", kDeck);
    add(register_entity_selection_commands, "Selection by and of solid-model entities",
        "docs/modeling.md");
    add(register_mesh_selection_commands, "Selection of nodes and elements", kDeck);
    add(register_surface_load_commands, "Surface loads", kDeck);
    add(register_material_commands, "Materials", "docs/plasticity.md");
    add(register_explicit_commands, "Explicit dynamics (ED commands)", "docs/explicit_dynamics.md");
    add(register_parameter_commands, "Parameters", kDeck);
    add(register_array_commands, "Arrays and vector operations", kDeck);
    add(register_output_commands, "Output (/OUTPUT, *VWRITE, *MSG)", kDeck);
    add(register_database_commands,
        "Database and restart files (SAVE, RESUME, /CLEAR, RESCONTROL, PARSAV)", kDeck);
    add(register_cdb_commands, "CDB archives (CDREAD, NBLOCK, EBLOCK, CMBLOCK, RLBLOCK)",
        "docs/meshes.md");
    add(register_workbench_commands,
        "Workbench input files: distributed files, diagnostics, CEWRITE, /XML", kDeck);
    return t;
  }();
  return tables;
}

}  // namespace

const std::vector<CommandSpec>& command_table() {
  return tables().commands;
}

const std::vector<CommandGroup>& command_groups() {
  return tables().groups;
}

const CommandSpec* find_command(const std::string& name) {
  // Hashed: loops run the lookup once per command executed.
  static const std::unordered_map<std::string, const CommandSpec*> index = [] {
    std::unordered_map<std::string, const CommandSpec*> m;
    for (const auto& spec : command_table()) m.emplace(spec.name, &spec);  // first one wins
    return m;
  }();
  const auto it = index.find(name);
  return it == index.end() ? nullptr : it->second;
}

const CommandSpec* find_command_by_abbreviation(const std::string& name, bool& ambiguous) {
  ambiguous = false;
  if (name.size() < 4) return nullptr;  // `/OUT`, `*STA`, `SECT`: four characters at least
  const CommandSpec* found = nullptr;
  for (const auto& spec : command_table()) {
    const std::string candidate = spec.name;
    if (candidate.size() <= name.size() || candidate.compare(0, name.size(), name) != 0) continue;
    if (found != nullptr && std::string(found->name) != candidate) {
      ambiguous = true;
      return nullptr;
    }
    found = &spec;
  }
  return found;
}

namespace {
/// Leading '/' or '*' (kept) plus the first four characters after it.
std::string significant(const std::string& name) {
  std::size_t lead = (!name.empty() && (name[0] == '/' || name[0] == '*')) ? 1 : 0;
  return name.substr(0, lead + 4);
}
}  // namespace

const CommandSpec* find_command_by_prefix(const std::string& name, bool& ambiguous) {
  ambiguous = false;
  const std::size_t lead = (!name.empty() && (name[0] == '/' || name[0] == '*')) ? 1 : 0;
  if (name.size() < lead + 4) return nullptr;
  const std::string key = significant(name);
  const CommandSpec* found = nullptr;
  for (const auto& spec : command_table()) {
    const std::string candidate = spec.name;
    if (candidate.size() < key.size()) continue;
    if (significant(candidate) != key) continue;
    if (found != nullptr) {
      ambiguous = true;
      return nullptr;
    }
    found = &spec;
  }
  return found;
}

const CommandSpec* find_command_by_longer_spelling(const std::string& name) {
  const std::size_t lead = (!name.empty() && (name[0] == '/' || name[0] == '*')) ? 1 : 0;
  if (name.size() <= lead + 4) return nullptr;
  bool several = false;
  const CommandSpec* spec = find_command_by_prefix(name, several);
  return several ? nullptr : spec;  // several commands share the four: the name is unknown
}

}  // namespace impactfe::deck
