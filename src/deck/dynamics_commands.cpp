// Dynamic analysis options: the transient method (TRNOPT), the integration parameters (TINTP),
// damping (ALPHAD, BETAD, DMPRAT, MDAMP), the modal extraction (MODOPT, MXPAND) and the
// mode-superposition load vector scale (LVSCALE); the harmonic response options (HROPT, HROUT,
// HARFRQ, DMPSTR).
#include <fmt/format.h>

#include <algorithm>

#include "deck/deck_context.h"

namespace impactfe::deck {

namespace {

void cmd_trnopt(DeckReader& r, const Command& c) {
  // TRNOPT,Method,MAXMODE,InitialAcc,MINMODE,MCout,TINTOPT,VAout,...
  AnalysisOptions& o = r.model.options;
  const std::string m = r.label(c, 1);
  if (m == "FULL" || m.empty())
    o.method = TransientMethod::Full;
  else if (m == "REDUC")
    o.method = TransientMethod::Reduced;
  else if (m == "MSUP")
    o.method = TransientMethod::ModeSuperposition;
  else
    r.fail(c, fmt::format("transient method '{}' not supported (FULL, REDUC, MSUP)", c.text(1)));
  if (!c.blank(2)) o.msup_modes = r.integer(c, 2, 0);
  if (!c.blank(4) && r.integer(c, 4, 1) != 1)
    r.fail(c, "MINMODE other than 1 is not supported (the superposition uses the modes from 1)");
  const std::string t = r.label(c, 6);
  if (t == "NMK" || t == "0")
    o.integrator = IntegratorKind::Newmark;
  else if (t == "HHT" || t == "1")
    o.integrator = IntegratorKind::HHT;
  else if (t == "HOUB")
    o.integrator = IntegratorKind::Houbolt;  // program extension (§9.4)
  else if (!t.empty())
    r.fail(c, fmt::format("bad TINTOPT '{}' (NMK, HHT, HOUB)", c.text(6)));
}

void cmd_tintp(DeckReader& r, const Command& c) {
  TimeIntegrationParameters& p = r.model.options.tintp;
  p.where = c.where;
  const std::string g = r.label(c, 1);
  if (g == "IMPA" || g == "HISP" || g == "MOSP" || g == "LOSP" || g == "QUAS")
    r.warn(c, fmt::format("application label {} ignored; default parameters used", g));
  else if (!g.empty())
    p.gamma = r.opt_real(c, 1);
  if (!c.blank(2)) p.alpha = r.opt_real(c, 2);
  if (!c.blank(3)) p.delta = r.opt_real(c, 3);
  if (!c.blank(10)) p.alpha_f = r.opt_real(c, 10);
  if (!c.blank(11)) p.alpha_m = r.opt_real(c, 11);
}

void cmd_alphad(DeckReader& r, const Command& c) {
  r.model.options.alpha_damping = r.real(c, 1, 0.0);
}
void cmd_betad(DeckReader& r, const Command& c) {
  r.model.options.beta_damping = r.real(c, 1, 0.0);
}
void cmd_dmprat(DeckReader& r, const Command& c) {
  r.model.options.damping_ratio = r.real(c, 1, 0.0);
}

void cmd_mdamp(DeckReader& r, const Command& c) {
  const int start = r.integer(c, 1, r.solution.mdamp_next);
  if (start <= 0) r.fail(c, "STLOC must be positive");
  for (int k = 0; k < 6; ++k) {
    if (c.blank(2 + k)) continue;
    r.model.options.modal_damping[start + k] = r.real(c, 2 + k, 0.0);
    r.solution.mdamp_next = std::max(r.solution.mdamp_next, start + k + 1);
  }
}

void cmd_modopt(DeckReader& r, const Command& c) {
  ModalOptions& m = r.model.options.modal;
  const std::string method = r.label(c, 1);
  if (!method.empty()) m.method = method;
  // QRDAMP projects the damping on the undamped modes (modal_analysis.cpp, damped_modes.h);
  // DAMP and UNSYM would need complex eigensolvers of the full matrices.
  if (method == "DAMP" || method == "UNSYM")
    r.warn(c, "damped/unsymmetric eigensolvers not available; undamped real modes computed");
  const auto n = r.opt_int(c, 2);
  if (!n) r.fail(c, "NMODE (number of modes) is required");
  if (*n <= 0) r.fail(c, fmt::format("NMODE {} must be positive", *n));
  m.n_modes = *n;
  m.freq_begin = r.opt_real(c, 3);
  m.freq_end = r.opt_real(c, 4);
  m.normalize_to_unity = r.label(c, 6) == "ON";
}

void cmd_mxpand(DeckReader& r, const Command& c) {
  // MXPAND,NMODE,FREQB,FREQE,Elcalc: every extracted mode is written (NMODE and the frequency
  // window do not narrow it); Elcalc YES also writes each mode's element results.
  Log::info("{}:{}: MXPAND: all extracted modes are kept in memory and written", c.where.file,
            c.where.line);
  const std::string elcalc = r.label(c, 4);
  if (elcalc == "YES" || elcalc == "ON" || elcalc == "1")
    r.model.options.modal.element_results = true;
  else if (elcalc.empty() || elcalc == "NO" || elcalc == "OFF" || elcalc == "0")
    r.model.options.modal.element_results = false;
  else
    r.fail(c, fmt::format("Elcalc '{}' must be YES or NO", c.text(4)));
}

void cmd_lvscale(DeckReader& r, const Command& c) {
  // LVSCALE,FACT,LDSTEP: the load vector of the modal analysis's load step LDSTEP, times FACT,
  // loads the mode-superposition transient from this load step on (ramped or stepped by KBC
  // from the previous step's factor, as any load). impactfe keeps the loads of the modal
  // analysis's load steps (F, ACEL, SF) and applies them again; no .mode file is involved.
  const auto fact = r.opt_real(c, 1);
  if (!fact) r.fail(c, "FACT (the load vector's scale factor) is missing");
  const int step = r.integer(c, 2, 1);
  if (step <= 0) r.fail(c, fmt::format("LDSTEP {} must be positive", step));
  const AnalysisOptions& o = r.model.options;
  if (o.type != AnalysisType::Transient || o.method != TransientMethod::ModeSuperposition)
    r.fail(c,
           "LVSCALE scales a modal analysis's load vector in a mode-superposition transient "
           "(ANTYPE,TRANS with TRNOPT,MSUP); the current analysis is not one");
  if (static_cast<std::size_t>(step) > r.model.modal_load_vectors.size())
    r.fail(c, r.model.modal_load_vectors.empty()
                  ? std::string("no modal analysis was solved before: there is no load vector "
                                "to scale")
                  : fmt::format("the modal analysis has {} load step(s), not {}",
                                r.model.modal_load_vectors.size(), step));
  r.model.current.load_vector_scale = *fact;
  r.model.current.load_vector_step = step;
}

void cmd_hropt(DeckReader& r, const Command& c) {
  // HROPT,Method,MAXMODE,MINMODE,MCout,Damp,...
  HarmonicOptions& h = r.model.options.harmonic;
  const std::string m = r.label(c, 1);
  if (m == "FULL" || m.empty())
    h.mode_superposition = false;
  else if (m == "MSUP")
    h.mode_superposition = true;
  else if (m == "HBM")
    r.fail(c, "the harmonic balance method (HROPT,HBM) is not supported (FULL, MSUP)");
  else
    r.fail(c, fmt::format("harmonic method '{}' not supported (FULL, MSUP)", c.text(1)));
  h.n_modes = 0;
  if (!c.blank(2)) {
    h.n_modes = r.integer(c, 2, 0);
    if (h.n_modes < 0) r.fail(c, fmt::format("MAXMODE {} must not be negative", h.n_modes));
  }
  if (!c.blank(3) && r.integer(c, 3, 1) != 1)
    r.fail(c, "MINMODE other than 1 is not supported (the superposition uses the modes from 1)");
  if (!c.blank(4) && r.label(c, 4) != "NO")
    r.fail(c, "MCout (modal coordinates file) is not supported");
}

void cmd_hrout(DeckReader& r, const Command& c) {
  // HROUT,Reimky,Clust,Mcont: Reimky ON prints real and imaginary parts, OFF amplitude and
  // phase; the results file always stores real and imaginary parts.
  HarmonicOptions& h = r.model.options.harmonic;
  h.amplitude_phase = !r.on_off(c, 1, true);
  if (r.on_off(c, 2, false))
    r.fail(c, "Clust ON (frequencies clustered about the natural frequencies) is not supported");
  if (r.on_off(c, 3, false)) r.fail(c, "Mcont ON (modal contributions printout) is not supported");
}

void cmd_harfrq(DeckReader& r, const Command& c) {
  // HARFRQ,FREQB,FREQE,--,LogOpt,FREQARR,Toler: FREQE blank means the single frequency FREQB.
  if (!c.blank(4)) r.fail(c, "LogOpt (logarithmic frequency spacing) is not supported");
  if (!c.blank(5)) r.fail(c, "FREQARR (a table of frequencies) is not supported");
  const double fb = r.real(c, 1, 0.0);
  const double fe = c.blank(2) ? fb : r.real(c, 2, 0.0);
  if (fb < 0.0 || fe < 0.0) r.fail(c, "frequencies must not be negative");
  if (fe < fb) r.fail(c, fmt::format("FREQE {:g} is below FREQB {:g}", fe, fb));
  if (fe <= 0.0) r.fail(c, "FREQE must be positive (the harmonic frequency in Hz)");
  r.model.current.frequency_range = std::make_pair(fb, fe);
}

void cmd_dmpstr(DeckReader& r, const Command& c) {
  const double g = r.real(c, 1, 0.0);
  if (g < 0.0) r.fail(c, fmt::format("structural damping coefficient {:g} is negative", g));
  // CDB archives write DMPSTR,0 whatever the analysis; a non-zero value acts in a harmonic
  // analysis only (i g K), so elsewhere it is refused rather than ignored.
  if (g != 0.0 && r.model.options.type != AnalysisType::Harmonic)
    r.fail(c,
           "a non-zero DMPSTR (structural damping) acts in a harmonic analysis only: give "
           "ANTYPE,HARMIC first");
  r.model.options.harmonic.structural_damping = g;
}

void cmd_rigid(DeckReader& r, const Command& c) {
  // RIGID,Dof1..Dof6: the known rigid-body modes of a component mode synthesis (its notes: the
  // command applies only to CMS, which CMSOPT refuses here). Elsewhere it has no effect, in
  // MAPDL as here: a modal analysis finds a free model's rigid-body modes itself.
  for (int k = 1; k <= c.n_fields(); ++k) {
    if (c.blank(k)) continue;
    const std::string dof = r.label(c, k);
    if (dof != "ALL" && dof != "UX" && dof != "UY" && dof != "UZ" && dof != "ROTX" &&
        dof != "ROTY" && dof != "ROTZ")
      r.fail(c, fmt::format("Dof{} '{}': ALL, UX, UY, UZ, ROTX, ROTY or ROTZ", k, c.text(k)));
  }
  r.ignore(c);
}

}  // namespace

void register_dynamics_commands(std::vector<CommandSpec>& t) {
  t.push_back({"TRNOPT", cmd_trnopt, kPrepSolu});
  t.push_back({"TINTP", cmd_tintp, kPrepSolu});
  t.push_back({"ALPHAD", cmd_alphad, kPrepSolu});
  t.push_back({"BETAD", cmd_betad, kPrepSolu});
  t.push_back({"DMPRAT", cmd_dmprat, kPrepSolu});
  t.push_back({"MDAMP", cmd_mdamp, kPrepSolu});
  t.push_back({"MODOPT", cmd_modopt, kPrepSolu});
  t.push_back({"RIGID", cmd_rigid, kPrepSolu,
               "acts only in a component mode synthesis (CMSOPT, refused): no effect elsewhere, "
               "as in MAPDL"});
  t.push_back({"MXPAND", cmd_mxpand, kPrepSolu});
  t.push_back({"LVSCALE", cmd_lvscale, kSolu});
  t.push_back({"HROPT", cmd_hropt, kPrepSolu});
  t.push_back({"HROUT", cmd_hrout, kPrepSolu});
  t.push_back({"HARFRQ", cmd_harfrq, kPrepSolu});
  t.push_back({"DMPSTR", cmd_dmpstr, kPrepSolu});
}

}  // namespace impactfe::deck
