// Session, processor and parameter commands; the control commands (*DO, *IF, /INPUT, ...) are
// listed here but executed by the executor in deck_reader.cpp.
#include <fmt/format.h>

#include "core/dof.h"
#include "deck/deck_context.h"

namespace impactfe::deck {

namespace {

void cmd_prep7(DeckReader& r, const Command&) {
  r.processor = kPrep7;
}

void cmd_solu(DeckReader& r, const Command&) {
  r.processor = kSolu;
}

void cmd_post(DeckReader& r, const Command& c) {
  r.processor = c.name == "/POST1" ? kPost1 : kPost26;
}

void cmd_finish(DeckReader& r, const Command& c) {
  if (r.processor == kStress && !r.stress_requests.empty()) {
    r.warn(c, "/STRESS block closed by FINISH without END; expansion requests kept");
    close_stress_block(r, r.stress_where);
  }
  r.processor = kBegin;
}

void cmd_title(DeckReader& r, const Command& c) {
  r.model.title = c.rest;
}

void cmd_com(DeckReader& r, const Command& c) {
  Log::info("{}:{}: /COM {}", c.where.file, c.where.line, c.rest);
}

void cmd_filname(DeckReader& r, const Command& c) {
  if (c.blank(1)) r.fail(c, "file name missing");
  if (r.jobname_from_option) {
    r.warn(c, fmt::format("jobname '{}' from the command line kept", r.model.jobname));
    return;
  }
  r.model.jobname = c.text(1);
}

bool reserved_label(const std::string& name) {
  return parse_dof_label(name).has_value() || parse_force_label(name).has_value() ||
         name == "ALL" || name == "ON" || name == "OFF";
}

void cmd_set(DeckReader& r, const Command& c) {
  const std::string name = r.label(c, 1);
  if (!is_parameter_name(name))
    r.fail(c, fmt::format("'{}' is not a valid parameter name", c.text(1)));
  if (reserved_label(name))
    r.fail(c, fmt::format("'{}' is a label and cannot be a parameter", name));
  if (c.assignment) {
    const std::string& expr = c.text(2);
    if (expr.empty()) {
      r.params.erase(name);
      return;
    }
    if (expr[0] == '\'') r.fail(c, "character parameters are not supported");
    try {
      r.params.set(name, evaluate(expr, r.params));
    } catch (const ExpressionError& e) {
      r.fail(c, fmt::format("bad expression '{}' ({})", expr, e.what()));
    }
    return;
  }
  if (c.blank(2)) {
    r.params.erase(name);
    r.increments.erase(name);
    return;
  }
  if (c.text(2)[0] == '\'') r.fail(c, "character parameters are not supported");
  r.params.set(name, r.real(c, 2, 0.0));
  if (!c.blank(3)) {
    if (r.dialect == Dialect::Classic4x) {
      r.increments[name] = r.real(c, 3, 0.0);  // §3.29: added after each *DO pass
    } else {
      r.warn(c, "array values VAL2.. ignored (scalar parameters only)");
    }
  }
}

void cmd_afun(DeckReader& r, const Command& c) {
  const std::string l = r.label(c, 1);
  if (l == "DEG")
    r.params.degrees = true;
  else if (l == "RAD" || l.empty())
    r.params.degrees = false;
  else
    r.fail(c, fmt::format("unknown angle unit '{}' (DEG or RAD)", c.text(1)));
}

/// Graphics-device and print-only commands with no effect on results or pictures: ignored with a
/// logged reason (and listed). The plot and print commands of POST1/POST26 and the view settings
/// a picture needs are handled in post1_plot_commands.cpp and post26_commands.cpp.
void cmd_graphics(DeckReader& r, const Command& c) {
  r.ignore(c);
}

}  // namespace

void register_session_commands(std::vector<CommandSpec>& t) {
  t.push_back({"/PREP7", cmd_prep7, kBegin | kPrep7 | kSolu | kPost});
  t.push_back({"/SOLU", cmd_solu, kBegin | kPrep7 | kSolu | kPost});
  t.push_back({"/POST1", cmd_post, kAnywhere});
  t.push_back({"/POST26", cmd_post, kAnywhere});
  t.push_back({"FINISH", cmd_finish, kAnywhere});
  t.push_back({"/TITLE", cmd_title, kAnywhere});
  t.push_back({"/COM", cmd_com, kAnywhere});
  t.push_back({"/FILNAME", cmd_filname, kBegin | kPrep7});
  t.push_back({"*SET", cmd_set, kAnywhere});
  t.push_back({"*AFUN", cmd_afun, kAnywhere});
  // Control commands, run by the executor.
  for (const char* name : {"*DO", "*ENDDO", "*IF", "*ELSEIF", "*ELSE", "*ENDIF", "*BEGIN", "*END",
                           "*CREATE", "*USE", "/INPUT", "/EOF"})
    t.push_back({name, nullptr, kAnywhere});
  for (const char* name :
       {"/INTER",    "/NOPR",   "/GOPR",   "/OUTPUT",  "/PNUM",   "/PBC",    "EPLOT",   "NPLOT",
        "/REPLOT",   "/ANGLE",  "/TRIAD",  "/PLOPTS",  "/WINDOW", "/DEVICE", "/RGB",    "/CONTOUR",
        "/EDGE",     "/ESHAPE", "/TYPE",   "/USER",    "/ZOOM",   "/HEADER", "/PAGE",   "/FORMAT",
        "/GRAPHICS", "/GFILE",  "/GLINE",  "/GCOLUMN", "/GROPT",  "/GTHK",   "/WAIT",   "/UIS",
        "/BATCH",    "/UNITS",  "/VERIFY", "/NERR",    "/GST",    "/CWD",    "/CONFIG", "/SYS",
        "NLIST",     "ELIST",   "ETLIST",  "DLIST",    "FLIST",   "MPLIST",  "RLIST",   "KLIST",
        "LLIST",     "/STATUS", "*STATUS", "*LIST",    "SAVE",    "/PSF",    "/PSYMB",  "GPLOT",
        "/LINE",     "/COLOR",  "LINES"})
    t.push_back({name, cmd_graphics, kAnywhere});
}

}  // namespace impactfe::deck
