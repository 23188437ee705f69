/// Integrator selection from the analysis options (TRNOPT/TINTP, spec §10.2-10.3).
#include "core/log.h"
#include "time/time_integrator.h"

namespace impactfe {
namespace {

constexpr double kDefaultAmplitudeDecay = 0.005;  // TINTP GAMMA default

/// Unconditional stability (linear case): Newmark needs gamma >= 1/2 and beta >= gamma/2
/// (Hughes 2000, §9.1.2); generalized-alpha needs alpha_m <= alpha_f <= 1/2, gamma >= 1/2 and
/// beta >= 1/4 + (alpha_f - alpha_m)/2 (Chung & Hulbert 1993). Other values are legal but only
/// conditionally stable, so say so in the log rather than refuse the deck.
void warn_if_conditionally_stable(const GeneralizedAlphaParameters& p) {
  const double tol = 1e-12;
  bool stable = p.gamma >= 0.5 - tol;
  if (p.alpha_f == 0.0 && p.alpha_m == 0.0) {
    stable = stable && p.beta >= 0.5 * p.gamma - tol;
  } else {
    stable = stable && p.alpha_m <= p.alpha_f + tol && p.alpha_f <= 0.5 + tol &&
             p.beta >= 0.25 + 0.5 * (p.alpha_f - p.alpha_m) - tol;
  }
  if (!stable) {
    Log::warn(
        "TINTP: beta = {:g}, gamma = {:g}, alpha_f = {:g}, alpha_m = {:g} is only conditionally "
        "stable",
        p.beta, p.gamma, p.alpha_f, p.alpha_m);
  }
}

}  // namespace

namespace {

std::unique_ptr<TimeIntegrator> make_integrator(const AnalysisOptions& options) {
  const TimeIntegrationParameters& t = options.tintp;
  switch (options.integrator) {
    case IntegratorKind::Houbolt:
      return make_houbolt();
    case IntegratorKind::Newmark: {
      GeneralizedAlphaParameters p;
      if (t.gamma) {
        p = GeneralizedAlphaParameters::newmark(*t.gamma);
      } else {
        // Explicit ALPHA/DELTA; a blank one takes its value from the default amplitude decay.
        const auto d = GeneralizedAlphaParameters::newmark(kDefaultAmplitudeDecay);
        p = GeneralizedAlphaParameters::newmark_beta_gamma(t.alpha.value_or(d.beta),
                                                           t.delta.value_or(d.gamma));
      }
      warn_if_conditionally_stable(p);
      Log::info("time integration: Newmark, beta = {:g}, gamma = {:g}", p.beta, p.gamma);
      return make_generalized_alpha(p);
    }
    case IntegratorKind::HHT: {
      GeneralizedAlphaParameters p;
      if (t.gamma) {
        p = GeneralizedAlphaParameters::hht(*t.gamma, 0.0);
      } else {
        p = GeneralizedAlphaParameters::hht(t.alpha_f.value_or(kDefaultAmplitudeDecay),
                                            t.alpha_m.value_or(0.0));
      }
      // Explicit ALPHA/DELTA override the beta/gamma derived from alpha_f, alpha_m.
      if (t.alpha) p.beta = *t.alpha;
      if (t.delta) p.gamma = *t.delta;
      warn_if_conditionally_stable(p);
      Log::info(
          "time integration: HHT-alpha, alpha_f = {:g}, alpha_m = {:g}, beta = {:g}, "
          "gamma = {:g}",
          p.alpha_f, p.alpha_m, p.beta, p.gamma);
      return make_generalized_alpha(p);
    }
  }
  return make_houbolt();
}

}  // namespace

std::unique_ptr<TimeIntegrator> make_time_integrator(const AnalysisOptions& options) {
  try {
    return make_integrator(options);
  } catch (const InputError& e) {
    // Bad parameters come from TINTP: name it.
    if (e.where().known() || !options.tintp.where.known()) throw;
    throw InputError(options.tintp.where, e.message());
  }
}

}  // namespace impactfe
