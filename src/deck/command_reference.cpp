#include "deck/command_reference.h"

#include <fmt/format.h>

#include <algorithm>

#include "core/text.h"
#include "deck/deck_context.h"
#include "elements/element_reference.h"

namespace impactfe::deck {

namespace {

/// The processors of a command as a deck writer names them.
std::string processors(unsigned mask) {
  if ((mask & kAnywhere) == kAnywhere) return "anywhere";
  std::string out;
  for (unsigned p : {kBegin, kPrep7, kSolu, kPost1, kPost26, kStress})
    if ((mask & p) != 0) out += (out.empty() ? "" : ", ") + std::string(processor_name(p));
  return out;
}

/// What the program does with the command.
std::string action(const CommandSpec& spec) {
  if (spec.refused != nullptr) return fmt::format("refused: {}", spec.refused);
  if (spec.ignored != nullptr) return fmt::format("accepted and ignored: {}", spec.ignored);
  if (spec.handler == nullptr) return "carried out by the executor (control flow)";
  return "carried out";
}

const CommandGroup& group_of(const CommandSpec& spec) {
  const auto& table = command_table();
  const auto index = static_cast<std::size_t>(&spec - table.data());
  for (const auto& g : command_groups())
    if (index >= g.begin && index < g.end) return g;
  return command_groups().back();
}

}  // namespace

std::string command_help(const std::string& name) {
  const std::string upper = to_upper(name);
  const CommandSpec* spec = find_command(upper);
  bool ambiguous = false;
  if (spec == nullptr) spec = find_command_by_abbreviation(upper, ambiguous);
  if (spec == nullptr) {
    if (cannot_change_results(upper))
      return fmt::format(
          "{}: not a command of impactfe; --skip-unknown skips it (graphics, printing or GUI "
          "only), otherwise a deck that uses it stops\n",
          upper);
    return "";
  }
  const CommandGroup& g = group_of(*spec);
  return fmt::format("{}\n  group:      {}\n  accepted:   {}\n  action:     {}\n  described:  {}\n",
                     spec->name, g.title, processors(spec->processors), action(*spec), g.doc);
}

std::string command_reference_markdown() {
  std::string out =
      "## Commands\n\n"
      "Generated from the command table (`impactfe help --markdown`; `impactfe help NAME` prints "
      "one entry). A command is carried out where it is accepted; anywhere else it stops the deck "
      "with its location. The page named under each group describes the fields and what is "
      "assumed. A command that is not listed stops the deck (\"unknown command\").\n";
  const auto& table = command_table();
  for (const auto& g : command_groups()) {
    out += fmt::format(
        "\n### {}\n\nDescribed in `{}`.\n\n| command | accepted in | action |\n"
        "|---|---|---|\n",
        g.title, g.doc);
    for (std::size_t i = g.begin; i < g.end; ++i)
      out += fmt::format("| `{}` | {} | {} |\n", table[i].name, processors(table[i].processors),
                         action(table[i]));
  }
  std::vector<std::string_view> skippable = commands_without_effect_on_results();
  std::sort(skippable.begin(), skippable.end());
  out +=
      "\n### Unknown commands that `--skip-unknown` skips\n\n"
      "Not carried out. Their only effect in MAPDL is on pictures, picture files, printed "
      "listings or the GUI, so `impactfe run --skip-unknown` skips them with a warning; without "
      "the option they stop the deck like any unknown command:\n\n";
  std::string line;
  for (const std::string_view name : skippable) {
    const std::string item = fmt::format("`{}`", name);
    if (!line.empty() && line.size() + item.size() + 1 > 98) {
      out += line + "\n";
      line.clear();
    }
    line += (line.empty() ? "" : " ") + item;
  }
  out += line + "\n";
  return out;
}

std::string reference_markdown() {
  return "# Command and element reference\n\n" + command_reference_markdown() + "\n" +
         element_reference_markdown();
}

std::string help_entry(const std::string& name) {
  if (const ElementTypeDescriptor* type = find_element_type(name)) return element_help(*type);
  return command_help(name);
}

std::string help_index() {
  return fmt::format(
      "impactfe help NAME: what impactfe does with a deck command (NSUBST, /UNITS, *GET) or an "
      "element type.\nElement types: {}\nAll commands and elements: impactfe help --markdown "
      "(docs/reference.md).\n",
      supported_element_type_names());
}

}  // namespace impactfe::deck
