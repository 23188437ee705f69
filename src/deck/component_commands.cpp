// Components (APDL_MODELING §1.7-1.9): CM, CMSEL, CMDELE, CMLIST. A component is a frozen list
// of entity numbers in Model::components; CMSEL applies it to the current selection (S, R, A, U,
// ALL, NONE), and node / element fields of other commands accept its name (post_support.h:
// component_members). The selection is the Model's (core/selection.h, the select commands of
// mesh_selection_commands.cpp).
#include <fmt/format.h>

#include <algorithm>
#include <cctype>
#include <set>

#include "deck/modeling_helpers.h"
#include "deck/post_support.h"

namespace impactfe::deck {

namespace {

std::string component_name(DeckReader& r, const Command& c, int field) {
  const std::string name = r.label(c, field);
  if (name.empty()) r.fail(c, "component name missing");
  // A leading underscore is allowed: MAPDL's hidden components, which Workbench input files
  // write (_FIXEDSU, _CM54UX_XP).
  const bool ok = (std::isalpha(static_cast<unsigned char>(name[0])) != 0 || name[0] == '_') &&
                  std::all_of(name.begin(), name.end(), [](unsigned char ch) {
                    return std::isalnum(ch) != 0 || ch == '_' || ch == '.';
                  });
  if (!ok || name.size() > 256)
    r.fail(c, fmt::format("'{}' is not a valid component name (a letter or '_', then letters, "
                          "digits, '_' or '.')",
                          c.text(field)));
  if (name == "ALL" || name == "STAT" || name == "DEFA")
    r.fail(c, fmt::format("'{}' is reserved and cannot name a component", name));
  return name;
}

std::string component_entity(DeckReader& r, const Command& c, int field) {
  const std::string e = r.label(c, field);
  if (e == "NODE" || e == "ELEM") return e;
  if (e == "KP" || e == "LINE" || e == "AREA" || e == "VOLU")
    r.fail(c, fmt::format("{} components are not supported (NODE and ELEM components only)", e));
  r.fail(c, fmt::format("Entity '{}': NODE or ELEM expected", c.text(field)));
}

void cmd_cm(DeckReader& r, const Command& c) {
  // CM,Cname,Entity,--,KOPT
  const std::string name = component_name(r, c, 1);
  Component comp;
  comp.entity = component_entity(r, c, 2);
  comp.ids = comp.entity == "NODE" ? selected_nodes(r) : selected_elements(r);
  if (comp.ids.empty())
    r.fail(c, fmt::format("no {} selected: component {} would be empty",
                          comp.entity == "NODE" ? "nodes" : "elements", name));
  comp.where = c.where;
  Log::info("{}:{}: CM: component {} = {} {}", c.where.file, c.where.line, name, comp.ids.size(),
            comp.entity);
  r.model.components[name] = std::move(comp);
}

void cmd_cmsel(DeckReader& r, const Command& c) {
  // CMSEL,Type,Name,Entity
  std::string t = r.label(c, 1);
  if (t.empty()) t = "S";
  if (t == "ALL" || t == "NONE") {
    const std::string only = r.label(c, 3);
    for (const auto& [name, comp] : r.model.components) {
      if (!only.empty() && comp.entity != only) continue;
      Selection& sel = comp.entity == "NODE" ? r.model.selection.nodes : r.model.selection.elements;
      const std::vector<int> defined =
          comp.entity == "NODE" ? all_ids(r.model.nodes) : all_ids(r.model.elements);
      std::set<int> m(comp.ids.begin(), comp.ids.end());
      sel.apply(t == "ALL" ? SelectType::Also : SelectType::Unselect, defined,
                [&](int id) { return m.count(id) != 0; });
    }
    return;
  }
  const auto type = parse_select_type(t);
  if (!type || (*type != SelectType::Select && *type != SelectType::Reselect &&
                *type != SelectType::Also && *type != SelectType::Unselect))
    r.fail(c, fmt::format("Type '{}': S, R, A, U, ALL or NONE expected", c.text(1)));
  const std::string name = r.label(c, 2);
  const auto it = r.model.components.find(name);
  if (it == r.model.components.end())
    r.fail(c, fmt::format("component '{}' is not defined (CM)", c.text(2)));
  const Component& comp = it->second;
  if (!r.label(c, 3).empty() && r.label(c, 3) != comp.entity)
    r.fail(c,
           fmt::format("component {} holds {} entities, not {}", name, comp.entity, r.label(c, 3)));
  const bool nodes = comp.entity == "NODE";
  Selection& sel = nodes ? r.model.selection.nodes : r.model.selection.elements;
  const std::vector<int> defined = nodes ? all_ids(r.model.nodes) : all_ids(r.model.elements);
  std::set<int> m(comp.ids.begin(), comp.ids.end());
  sel.apply(*type, defined, [&](int id) { return m.count(id) != 0; });
  const std::size_t n = sel.selected_of(defined).size();
  Log::info("{}:{}: CMSEL: {} {} selected (of {})", c.where.file, c.where.line, n,
            nodes ? "nodes" : "elements", defined.size());
  if (n == 0) r.warn(c, fmt::format("no {} selected", nodes ? "nodes" : "elements"));
}

void cmd_cmdele(DeckReader& r, const Command& c) {
  const std::string name = r.label(c, 1);
  if (name == "ALL" || name.empty()) {
    r.model.components.clear();
    return;
  }
  if (r.model.components.erase(name) == 0)
    r.fail(c, fmt::format("component '{}' is not defined", c.text(1)));
}

void cmd_cmlist(DeckReader& r, const Command& c) {
  // CMLIST,Name,Key (Key 1: list the members too)
  const std::string only = r.label(c, 1);
  const bool members = r.integer(c, 2, 0) == 1;
  if (!only.empty() && only != "ALL" && r.model.components.count(only) == 0)
    r.fail(c, fmt::format("component '{}' is not defined", c.text(1)));
  std::string out = "\n LIST COMPONENTS\n\n  NAME                             TYPE     SIZE\n";
  for (const auto& [name, comp] : r.model.components) {
    if (!only.empty() && only != "ALL" && name != only) continue;
    out += fmt::format("  {:<32} {:<8} {:>6}\n", name, comp.entity, comp.ids.size());
    if (members)
      for (std::size_t k = 0; k < comp.ids.size(); k += 8) {
        out += "   ";
        for (std::size_t j = k; j < std::min(k + 8, comp.ids.size()); ++j)
          out += fmt::format("{:>9}", comp.ids[j]);
        out += "\n";
      }
  }
  print(r, out);
}

}  // namespace

void register_component_commands(std::vector<CommandSpec>& t) {
  constexpr unsigned where = kPrep7 | kSolu | kPost1 | kPost26;
  t.push_back({"CM", cmd_cm, where});
  t.push_back({"CMSEL", cmd_cmsel, where});
  t.push_back({"CMDELE", cmd_cmdele, where});
  t.push_back({"CMLIST", cmd_cmlist, kAnywhere});
}

}  // namespace impactfe::deck
