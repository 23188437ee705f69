// POST1 / POST26 commands: stored (with parameters substituted) in Job::post_commands for the
// post-processing stage; never executed here.
#include <fmt/format.h>

#include <cctype>

#include "deck/deck_context.h"

namespace impactfe::deck {

namespace {

/// A field as the post stage should see it: numbers kept, a defined parameter or an expression
/// made only of defined parameters replaced by its value, anything else upper-cased (labels).
std::string substitute(const DeckReader& r, const std::string& text) {
  if (text.empty() || parse_fortran_number(text)) return text;
  bool has_letter = false;
  for (char ch : text) has_letter = has_letter || std::isalpha(static_cast<unsigned char>(ch));
  if (!has_letter) {
    try {
      return fmt::format("{}", evaluate(text, r.params));
    } catch (const ExpressionError&) {
      return text;
    }
  }
  try {
    return fmt::format("{}", evaluate(text, r.params));
  } catch (const ExpressionError&) {
    return to_upper(text);  // a label such as U, X, ALL, LAST
  }
}

void cmd_post_only(DeckReader& r, const Command& c) {
  store_post_command(r, c);
}

}  // namespace

void store_post_command(DeckReader& r, const Command& c) {
  StoredCommand s;
  s.name = c.name;
  s.where = c.where;
  for (const auto& f : c.fields) s.fields.push_back(substitute(r, f));
  r.job.post_commands.push_back(std::move(s));
}

void register_post_commands(std::vector<CommandSpec>& t) {
  for (const char* name :
       {"SET",   "NSOL",   "ESOL",  "RFORCE", "GAPF",        "DERIV",    "INT1",   "NUMVAR",
        "ADD",   "PROD",   "QUOT",  "ABS",    "SQRT",        "FILLDATA", "EXTREM", "TIMERANGE",
        "STORE", "NSORT",  "ESORT", "ETABLE", "NSEL",        "ESEL",     "ALLSEL", "FSUM",
        "SOLU",  "VARNAM", "LINES", "/GRID",  "/XRANGE_POST"})
    t.push_back({name, cmd_post_only, kPost});
}

}  // namespace impactfe::deck
