/// Integrator selection from the analysis options (TRNOPT/TINTP, spec §10.2-10.3).
#include "core/log.h"
#include "time/time_integrator.h"

namespace impactfe {
namespace {

constexpr double kDefaultAmplitudeDecay = 0.005;  // TINTP GAMMA default

/// Newmark is unconditionally stable for gamma >= 1/2 and beta >= (1/2 + gamma)^2 / 4
/// (Hughes 2000, §9.1); other values are legal but conditionally stable, so say so in the log.
void warn_if_conditionally_stable(const GeneralizedAlphaParameters& p) {
  const double s = 0.5 + p.gamma - p.alpha_f + p.alpha_m;
  if (p.gamma < 0.5 || p.beta < 0.25 * s * s - 1e-12) {
    Log::warn(
        "TINTP: beta = {:g}, gamma = {:g} is only conditionally stable (unconditional "
        "stability needs gamma >= 1/2 and beta >= (1/2 + gamma)^2/4)",
        p.beta, p.gamma);
  }
}

}  // namespace

std::unique_ptr<TimeIntegrator> make_time_integrator(const AnalysisOptions& options) {
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

}  // namespace impactfe
