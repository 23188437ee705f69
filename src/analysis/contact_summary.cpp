#include "analysis/contact_summary.h"

#include <fmt/format.h>

#include <algorithm>

namespace impactfe {

std::optional<std::string> contact_summary(const std::vector<std::unique_ptr<Element>>& elements,
                                           const Assembler& assembler, const VectorXd& u,
                                           int load_step, double time) {
  int n = 0, closed = 0, sliding = 0, deepest = 0;
  double penetration = 0.0, force = 0.0;
  VectorXd ue;
  ElementResultValues out;
  for (std::size_t e = 0; e < elements.size(); ++e) {
    const Element& el = *elements[e];
    if (!el.has_status()) continue;
    const auto& names = el.result_names();
    const auto at = [&](const char* name) {
      return static_cast<int>(std::find(names.begin(), names.end(), name) - names.begin());
    };
    const int stat = at("STAT"), fn = at("FN"), pene = at("PENE");
    const int size = static_cast<int>(names.size());
    if (stat == size || fn == size || pene == size) continue;
    ++n;
    assembler.gather(e, u, ue);
    const VectorXd v = VectorXd::Zero(ue.size());
    el.results(assembler.context(), ue, v, out);
    // Contact status codes: 0 far open, 1 near open, 2 sliding, 3 sticking.
    if (out[stat] >= 2.0) ++closed;
    if (out[stat] == 2.0) ++sliding;
    if (out[pene] > penetration) {
      penetration = out[pene];
      deepest = el.id();
    }
    force += out[fn];
  }
  if (n == 0) return std::nullopt;
  return fmt::format(
      "contact at the end of load step {} (t = {:g}): {} of {} contact elements closed ({} "
      "sliding), max penetration {:.4g}{}, total normal force {:.6g}",
      load_step, time, closed, n, sliding, penetration,
      deepest != 0 ? fmt::format(" (element {})", deepest) : "", force);
}

}  // namespace impactfe
