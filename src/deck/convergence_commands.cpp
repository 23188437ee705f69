// Equilibrium-iteration commands: the Newton variant (KRF, NROPT), the line search (LNSRCH),
// the iteration limit (NEQIT) and the convergence criteria (CNVTOL); docs/solution_control.md.
#include <fmt/format.h>

#include "deck/deck_context.h"

namespace impactfe::deck {

namespace {

void cmd_krf(DeckReader& r, const Command& c) {
  const int n = r.integer(c, 1, 1);
  if (n <= 0) r.fail(c, fmt::format("re-formulation interval {} must be positive", n));
  r.model.current.reformulation = n;
  r.model.options.convergence.full_newton = n == 1;
}

void cmd_nropt(DeckReader& r, const Command& c) {
  const std::string l = r.label(c, 1);
  ConvergenceOptions& cv = r.model.options.convergence;
  if (l == "FULL" || l == "AUTO" || l.empty()) {
    cv.full_newton = true;
    r.model.current.reformulation = 1;
  } else if (l == "MODI" || l == "INIT") {
    cv.full_newton = false;
    r.model.current.reformulation = l == "INIT" ? 1000000 : 1;
  } else if (l == "UNSYM") {
    r.warn(c, "UNSYM treated as FULL (symmetric matrices)");
    cv.full_newton = true;
  } else {
    r.fail(c, fmt::format("bad option '{}' (FULL, MODI, INIT, AUTO)", c.text(1)));
  }
}

void cmd_lnsrch(DeckReader& r, const Command& c) {
  // LNSRCH,Key: ON, OFF (blank) or AUTO (MAPDL: switched on where it is needed; here, for the
  // corrections after one that raised the residual norm, docs/solution_control.md).
  const std::string key = r.label(c, 1);
  ConvergenceOptions& cv = r.model.options.convergence;
  cv.line_search = key == "ON" || key == "1" || key == "YES";
  cv.line_search_auto = key == "AUTO" || key == "-1";
  if (!cv.line_search && !cv.line_search_auto && !key.empty() && key != "OFF" && key != "0" &&
      key != "NO")
    r.fail(c, fmt::format("bad key '{}' (ON, OFF, AUTO)", c.text(1)));
}

void cmd_neqit(DeckReader& r, const Command& c) {
  // NITER 0 or blank: the program chooses (CDB archives write NEQIT,0); impactfe's choice is 25.
  int n = r.integer(c, 1, 25);
  if (n == 0) n = 25;
  if (n < 0) r.fail(c, fmt::format("NEQIT {} must be positive", n));
  r.model.options.convergence.max_iterations = n;
  if (r.label(c, 2) == "FORCE") r.model.options.convergence.max_iterations = 1;
}

void cmd_cnvtol(DeckReader& r, const Command& c) {
  const std::string lab = r.label(c, 1);
  ConvergenceOptions& cv = r.model.options.convergence;
  const auto value = r.opt_real(c, 2);
  if (lab == "F" || lab == "M") {
    if (value && *value < 0.0) {
      r.warn(c, "removing the force criterion is not supported; kept");
      return;
    }
    cv.force_tolerance = r.real(c, 3, 0.005);
    cv.force_minref = r.real(c, 5, cv.force_minref);
  } else if (lab == "U" || lab == "ROT") {
    if (value && *value < 0.0)
      cv.displacement_tolerance.reset();
    else
      cv.displacement_tolerance = r.real(c, 3, 0.05);
  } else {
    r.fail(c, fmt::format("bad label '{}' (F, M, U, ROT)", c.text(1)));
  }
}

}  // namespace

void register_convergence_commands(std::vector<CommandSpec>& t) {
  t.push_back({"KRF", cmd_krf, kPrepSolu});
  t.push_back({"NROPT", cmd_nropt, kPrepSolu});
  t.push_back({"NEQIT", cmd_neqit, kPrepSolu});
  t.push_back({"LNSRCH", cmd_lnsrch, kPrepSolu});
  t.push_back({"CNVTOL", cmd_cnvtol, kPrepSolu});
}

}  // namespace impactfe::deck
