// Session and processor commands; the control commands (*DO, *IF, /INPUT, ...) are listed here
// but run by the executor (control_flow.cpp).
#include <fmt/format.h>

#include <algorithm>
#include <iterator>

#include "core/dof.h"
#include "core/files.h"
#include "core/log.h"
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
  if (r.processor == kStress && !r.solution.stress_requests.empty()) {
    r.warn(c, "/STRESS block closed by FINISH without END; expansion requests kept");
    close_stress_block(r, r.solution.stress_where);
  }
  // Leaving /SOLU ends the analysis (MAPDL): the next SOLVE begins a new one unless ANTYPE,,REST
  // continues it. A 4.2 deck's analysis is the one its AFWRITE froze (no SOLVE).
  if (r.processor == kSolu && r.solution.open_analysis) {
    r.solution.open_analysis.reset();
    r.solution.finished_analysis = true;
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

/// Commands accepted and not carried out (graphics devices, print-only listings, MAPDL session
/// settings without a counterpart): ignored with the reason their table entry gives. The plot and
/// print commands of POST1/POST26 and the view settings a picture needs are handled in
/// post1_plot_commands.cpp and post26_commands.cpp.
void cmd_ignored(DeckReader& r, const Command& c) {
  r.ignore(c);
}

/// /UNITS,Label: records the unit system. As in MAPDL, a marker only: nothing is converted, the
/// deck's numbers are used as given; the label is written into the results file.
void cmd_units(DeckReader& r, const Command& c) {
  static const char* kSystems[] = {"USER", "SI", "MKS", "UMKS", "CGS", "MPA", "BFT", "BIN"};
  const std::string label = c.blank(1) ? std::string("USER") : r.label(c, 1);
  const bool known = std::find_if(std::begin(kSystems), std::end(kSystems),
                                  [&](const char* s) { return label == s; }) != std::end(kSystems);
  if (!known)
    r.fail(c, fmt::format("unit system '{}' unknown (USER, SI, MKS, uMKS, CGS, MPA, BFT, BIN)",
                          label));
  for (int i = 2; i <= c.n_fields(); ++i)
    if (!c.blank(i))
      r.fail(c, "USER conversion factors are not recorded: give the system label alone");
  r.model.units = label == "UMKS" ? "uMKS" : label;
  Log::info("{}:{}: /UNITS: unit system {} recorded (a marker: nothing is converted)", c.where.file,
            c.where.line, r.model.units);
}

/// A refused command's handler: never called (DeckReader::dispatch fails with its message).
void cmd_refused_session(DeckReader&, const Command&) {}

}  // namespace

void register_session_commands(std::vector<CommandSpec>& t) {
  t.push_back({"/PREP7", cmd_prep7, kBegin | kPrep7 | kSolu | kPost});
  t.push_back({"/SOLU", cmd_solu, kBegin | kPrep7 | kSolu | kPost});
  t.push_back({"/POST1", cmd_post, kAnywhere});
  t.push_back({"/POST26", cmd_post, kAnywhere});
  t.push_back({"FINISH", cmd_finish, kAnywhere});
  t.push_back({"/TITLE", cmd_title, kAnywhere});
  t.push_back({"/FILNAME", cmd_filname, kBegin | kPrep7});
  // The spelling of the Verification Manual decks (vm149, vmr029-t4-*), which MAPDL runs as
  // /FILNAME; its first four characters (/FILE) differ, so the 4x rule does not find it.
  t.push_back({"/FILENAME", cmd_filname, kBegin | kPrep7});
  // Control commands, run by the executor.
  for (const char* name :
       {"*DO", "*DOWHILE", "*ENDDO", "*IF", "*ELSEIF", "*ELSE", "*ENDIF", "*EXIT", "*CYCLE", "*GO",
        "*BEGIN", "*END", "*CREATE", "*USE", "/INPUT", "/EOF", "/EXIT", "*REPEAT"})
    t.push_back({name, nullptr, kAnywhere});
  for (const char* name :
       {"/INTER",  "/NOPR",   "/GOPR",    "/PNUM",   "/PBC",    "EPLOT",  "NPLOT",    "/REPLOT",
        "/ANGLE",  "/TRIAD",  "/PLOPTS",  "/WINDOW", "/DEVICE", "/RGB",   "/CONTOUR", "/EDGE",
        "/ESHAPE", "/TYPE",   "/USER",    "/ZOOM",   "/HEADER", "/PAGE",  "/FORMAT",  "/GRAPHICS",
        "/GFILE",  "/GLINE",  "/GCOLUMN", "/GROPT",  "/GTHK",   "/WAIT",  "/UIS",     "/GST",
        "NLIST",   "ELIST",   "ETLIST",   "DLIST",   "FLIST",   "MPLIST", "RLIST",    "KLIST",
        "LLIST",   "/STATUS", "/PSF",     "/PSYMB",  "GPLOT",   "/LINE",  "/COLOR",   "LINES",
        "CSLIST",  "SFLLIST"})
    t.push_back({name, cmd_ignored, kAnywhere, "graphics or printing only: no effect on results"});
  t.push_back({"/CONFIG", cmd_ignored, kAnywhere,
               "MAPDL's memory and file sizing has no counterpart here"});
  t.push_back({"/NERR", cmd_ignored, kAnywhere, "error limits: impactfe stops at the first error"});
  for (const char* name : {"/BATCH", "/VERIFY"})
    t.push_back({name, cmd_ignored, kAnywhere, "a mode that does not change a run here"});
  t.push_back({"/GO", cmd_ignored, kAnywhere, "printout on again (after /NOPR): printing only"});
  // Lines every CDB archive carries.
  t.push_back({"DOF", cmd_ignored, kPrep7 | kSolu,
               "the degrees of freedom follow from the element types here"});
  t.push_back({"MODCONTROL", cmd_ignored, kPrep7 | kSolu,
               "MAPDL's modal results-file control: the modes are stored the same way here"});
  t.push_back({"QRDOPT", cmd_ignored, kPrep7 | kSolu,
               "options of MAPDL's QR damped eigensolver (factor reuse, the symmetric solver, "
               "contribution printout): none changes the damped modes of MODOPT,QRDAMP"});
  // Lines every Workbench input file (ds.dat) carries.
  t.push_back({"/WB", cmd_ignored, kAnywhere,
               "marks the sections of a Workbench input file: no effect on the model"});
  t.push_back({"/NOLIST", cmd_ignored, kAnywhere, "input echo off: printing only"});
  t.push_back({"/GOLIST", cmd_ignored, kAnywhere, "input echo on: printing only"});
  t.push_back({"SHPP", cmd_ignored, kAnywhere,
               "MAPDL's element shape warnings; impactfe's own element checks (zero or negative "
               "volume or area) always run and cannot be switched off"});
  t.push_back({"ETCONTROL", cmd_ignored, kAnywhere,
               "MAPDL's automatic choice of the 18x elements' KEYOPTs; impactfe keeps the KEYOPTs "
               "as the input gives them (a Workbench input file writes them)"});
  t.push_back({"/UNITS", cmd_units, kAnywhere});
  // /CWD would move the run's files out of its directory; /SYS would run programs: refused.
  t.push_back({"/CWD", cmd_refused_session, kAnywhere, nullptr,
               "not carried out: the run's files go to its directory (impactfe run -o DIR); "
               "remove /CWD and give the directory on the command line"});
  t.push_back({"/SYS", cmd_refused_session, kAnywhere, nullptr,
               "operating-system commands are not run by impactfe; run them outside the deck"});
}

}  // namespace impactfe::deck
