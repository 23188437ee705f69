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

const std::vector<CommandSpec>& command_table() {
  static const std::vector<CommandSpec> table = [] {
    std::vector<CommandSpec> t;
    register_session_commands(t);
    register_prep7_commands(t);
    register_generation_commands(t);
    register_solution_commands(t);
    register_load_commands(t);
    register_component_commands(t);
    register_get_commands(t);
    register_post1_commands(t);
    register_post1_plot_commands(t);
    register_post26_commands(t);
    register_csys_commands(t);
    register_solid_model_commands(t);
    register_solid_edit_commands(t);
    register_mesh_commands(t);
    register_contact_commands(t);
    register_entity_selection_commands(t);
    register_mesh_selection_commands(t);
    register_surface_load_commands(t);
    register_material_commands(t);
    register_parameter_commands(t);
    register_array_commands(t);
    register_output_commands(t);
    register_database_commands(t);
    return t;
  }();
  return table;
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
