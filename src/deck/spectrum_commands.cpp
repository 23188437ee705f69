// Single-point response spectrum options (ANTYPE,SPECTR; docs/spectrum_analysis.md): the
// spectrum type (SPOPT), the excitation direction (SED), the spectrum table (SVTYP, FREQ, SV),
// the mode combination (SRSS, CQC, GRP, DSUM, NRLSUM) and the missing mass response (MMASS).
#include <fmt/format.h>

#include "deck/deck_context.h"

namespace impactfe::deck {

namespace {

SpectrumOptions& spectrum(DeckReader& r) {
  return r.model.options.spectrum;
}

void cmd_spopt(DeckReader& r, const Command& c) {
  // SPOPT,Sptype,NMODE,Elcalc,modeReuseKey.
  const std::string type = r.label(c, 1);
  if (type == "PSD")
    r.fail(c,
           "random vibration (SPOPT,PSD) is not supported (single-point response spectrum "
           "SPRS only)");
  if (type == "MPRS" || type == "DDAM")
    r.fail(c, fmt::format("{} spectrum analysis is not supported (SPRS only)", type));
  if (type != "SPRS") r.fail(c, fmt::format("spectrum type '{}' not supported (SPRS)", c.text(1)));
  SpectrumOptions& s = spectrum(r);
  s.single_point = true;
  s.where = c.where;
  s.n_modes = r.integer(c, 2, 0);
  if (s.n_modes < 0) r.fail(c, fmt::format("NMODE {} must not be negative", s.n_modes));
  const std::string elcalc = r.label(c, 3);
  if (elcalc == "YES" || elcalc == "ON" || elcalc == "1")
    s.element_results = true;
  else if (elcalc.empty() || elcalc == "NO" || elcalc == "OFF" || elcalc == "0")
    s.element_results = false;
  else
    r.fail(c, fmt::format("Elcalc '{}' must be YES or NO", c.text(3)));
  const std::string reuse = r.label(c, 4);
  if (!reuse.empty() && reuse != "NO")
    r.fail(c, "modeReuseKey YES (several spectrum solutions reusing the modes) is not supported");
}

void cmd_sed(DeckReader& r, const Command& c) {
  // SED,SEDX,SEDY,SEDZ,Cname: a point on the line of the excitation direction.
  if (!c.blank(4))
    r.fail(c, "Cname (excitation of a component's constrained nodes) is not supported");
  spectrum(r).direction = Vec3(r.real(c, 1, 0.0), r.real(c, 2, 0.0), r.real(c, 3, 0.0));
}

void cmd_svtyp(DeckReader& r, const Command& c) {
  // SVTYP,KSV,FACT,KeyInterp.
  const int ksv = r.integer(c, 1, 0);
  if (ksv == 1)
    r.fail(c, "the force spectrum (SVTYP,1) is not supported (seismic spectra 0, 2, 3)");
  if (ksv == 4) r.fail(c, "the PSD spectrum (SVTYP,4) is not supported (seismic spectra 0, 2, 3)");
  if (ksv != 0 && ksv != 2 && ksv != 3)
    r.fail(c, fmt::format("KSV {} is not a spectrum type (0 velocity, 2 acceleration, 3 "
                          "displacement)",
                          ksv));
  SpectrumOptions& s = spectrum(r);
  s.spectrum_type = ksv;
  s.scale = r.real(c, 2, 1.0);
  s.linear_interpolation = r.on_off(c, 3, false);
}

void cmd_freq(DeckReader& r, const Command& c) {
  // FREQ,FREQ1..FREQ9: appended after the frequencies already given; all blank erases the table.
  SpectrumOptions& s = spectrum(r);
  bool any = false;
  for (int f = 1; f <= 9; ++f) {
    if (c.blank(f)) continue;
    const double v = r.real(c, f, 0.0);
    if (v <= 0.0) continue;  // zero fields are not frequencies (values go after the last one)
    if (!s.frequencies.empty() && v <= s.frequencies.back())
      r.fail(c, fmt::format("frequency {:g} is not above the previous one {:g} (ascending order)",
                            v, s.frequencies.back()));
    s.frequencies.push_back(v);
    any = true;
  }
  if (!any) {
    s.frequencies.clear();
    s.curves.clear();
  }
}

void cmd_sv(DeckReader& r, const Command& c) {
  // SV,DAMP,SV1..SV9: the values of the curve of damping ratio DAMP, appended to the values it
  // has (a new curve for a new, higher damping ratio).
  SpectrumOptions& s = spectrum(r);
  const double damping = r.real(c, 1, 0.0);
  if (damping < 0.0) r.fail(c, fmt::format("DAMP {:g} must not be negative", damping));
  std::vector<double>* values = nullptr;
  for (auto& [d, v] : s.curves)
    if (d == damping) values = &v;
  if (!values) {
    if (!s.curves.empty() && damping < s.curves.back().first)
      r.fail(c, fmt::format("DAMP {:g} is below the previous curve's {:g} (ascending order)",
                            damping, s.curves.back().first));
    if (s.curves.size() >= 4) r.fail(c, "at most four spectrum curves (DAMP values)");
    s.curves.emplace_back(damping, std::vector<double>{});
    values = &s.curves.back().second;
  }
  for (int f = 2; f <= 10; ++f)
    if (!c.blank(f)) values->push_back(r.real(c, f, 0.0));
}

void combination(DeckReader& r, const Command& c, const char* method) {
  SpectrumOptions& s = spectrum(r);
  s.combination = method;
  s.significance = r.real(c, 1, 0.001);
  const std::string label = r.label(c, 2);
  if (label.empty() || label == "DISP")
    s.response = "DISP";
  else if (label == "VELO" || label == "ACEL")
    s.response = label;
  else
    r.fail(c, fmt::format("Label '{}' not supported (DISP, VELO, ACEL)", c.text(2)));
  const std::string force = r.label(c, 4);
  if (!force.empty() && force != "STATIC")
    r.fail(c, fmt::format("ForceType '{}' not supported (STATIC: the element forces of the "
                          "combined displacements)",
                          c.text(4)));
}

void cmd_srss(DeckReader& r, const Command& c) {
  // SRSS,SIGNIF,Label,AbsSumKey,ForceType.
  if (r.on_off(c, 3, false))
    r.fail(c, "AbsSumKey ON (absolute sum over excitation points) is not supported");
  combination(r, c, "SRSS");
}

void cmd_cqc(DeckReader& r, const Command& c) {
  // CQC,SIGNIF,Label,,ForceType.
  if (!c.blank(3)) r.fail(c, fmt::format("field 3 '{}' is not a CQC field", c.text(3)));
  combination(r, c, "CQC");
}

void cmd_grp(DeckReader& r, const Command& c) {
  // GRP,SIGNIF,Label,,ForceType.
  if (!c.blank(3)) r.fail(c, fmt::format("field 3 '{}' is not a GRP field", c.text(3)));
  combination(r, c, "GRP");
}

void cmd_dsum(DeckReader& r, const Command& c) {
  // DSUM,SIGNIF,Label,TD,ForceType: TD the duration of the excitation (default 10).
  const double td = r.real(c, 3, 10.0);
  if (td <= 0.0) r.fail(c, fmt::format("TD {:g} must be positive", td));
  combination(r, c, "DSUM");
  spectrum(r).duration = td;
}

void cmd_nrlsum(DeckReader& r, const Command& c) {
  // NRLSUM,SIGNIF,Label,LabelCSM,ForceType.
  if (!c.blank(3))
    r.fail(c, "LabelCSM (closely spaced modes of the NRL-1677 sum) is not supported");
  combination(r, c, "NRLSUM");
}

void cmd_mmass(DeckReader& r, const Command& c) {
  // MMASS,Option,ZPA: the missing mass response at the zero period acceleration ZPA.
  SpectrumOptions& s = spectrum(r);
  s.missing_mass = r.on_off(c, 1, false);
  if (!s.missing_mass) return;
  const auto zpa = r.opt_real(c, 2);
  if (!zpa) r.fail(c, "ZPA (the zero period acceleration) is required with MMASS,ON");
  s.zero_period_acceleration = *zpa;
}

}  // namespace

void register_spectrum_commands(std::vector<CommandSpec>& t) {
  t.push_back({"SPOPT", cmd_spopt, kPrepSolu});
  t.push_back({"SED", cmd_sed, kPrepSolu});
  t.push_back({"SVTYP", cmd_svtyp, kPrepSolu});
  t.push_back({"FREQ", cmd_freq, kPrepSolu});
  t.push_back({"SV", cmd_sv, kPrepSolu});
  t.push_back({"SRSS", cmd_srss, kSolu});
  t.push_back({"CQC", cmd_cqc, kSolu});
  t.push_back({"GRP", cmd_grp, kSolu});
  t.push_back({"DSUM", cmd_dsum, kSolu});
  t.push_back({"NRLSUM", cmd_nrlsum, kSolu});
  t.push_back({"MMASS", cmd_mmass, kPrepSolu});
}

}  // namespace impactfe::deck
