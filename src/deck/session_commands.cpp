// Session and processor commands; the control commands (*DO, *IF, /INPUT, ...) are listed here
// but run by the executor (control_flow.cpp).
#include <fmt/format.h>

#include "core/dof.h"
#include "core/files.h"
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

void cmd_filname(DeckReader& r, const Command& c) {
  if (c.blank(1)) r.fail(c, "file name missing");
  if (r.jobname_from_option) {
    r.warn(c, fmt::format("jobname '{}' from the command line kept", r.model.jobname));
    return;
  }
  if (const std::string problem = jobname_problem(c.text(1)); !problem.empty()) r.fail(c, problem);
  r.model.jobname = c.text(1);
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
  t.push_back({"/FILNAME", cmd_filname, kBegin | kPrep7});
  // Control commands, run by the executor.
  for (const char* name :
       {"*DO", "*DOWHILE", "*ENDDO", "*IF", "*ELSEIF", "*ELSE", "*ENDIF", "*EXIT", "*CYCLE", "*GO",
        "*BEGIN", "*END", "*CREATE", "*USE", "/INPUT", "/EOF", "*REPEAT"})
    t.push_back({name, nullptr, kAnywhere});
  for (const char* name :
       {"/INTER",  "/NOPR",   "/GOPR",    "/PNUM",   "/PBC",    "EPLOT",   "NPLOT",    "/REPLOT",
        "/ANGLE",  "/TRIAD",  "/PLOPTS",  "/WINDOW", "/DEVICE", "/RGB",    "/CONTOUR", "/EDGE",
        "/ESHAPE", "/TYPE",   "/USER",    "/ZOOM",   "/HEADER", "/PAGE",   "/FORMAT",  "/GRAPHICS",
        "/GFILE",  "/GLINE",  "/GCOLUMN", "/GROPT",  "/GTHK",   "/WAIT",   "/UIS",     "/BATCH",
        "/UNITS",  "/VERIFY", "/NERR",    "/GST",    "/CWD",    "/CONFIG", "/SYS",     "NLIST",
        "ELIST",   "ETLIST",  "DLIST",    "FLIST",   "MPLIST",  "RLIST",   "KLIST",    "LLIST",
        "/STATUS", "/PSF",    "/PSYMB",   "GPLOT",   "/LINE",   "/COLOR",  "LINES"})
    t.push_back({name, cmd_graphics, kAnywhere});
}

}  // namespace impactfe::deck
