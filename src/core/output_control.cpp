#include "core/output_control.h"

#include <algorithm>
#include <deque>
#include <mutex>

#include "core/errors.h"

namespace impactfe {

namespace {

/// Registered per-item settings; a deque keeps references stable as it grows.
struct Registry {
  std::mutex mutex;
  std::deque<OutputControl> controls;
};

Registry& registry() {
  static Registry r;
  return r;
}

}  // namespace

bool OutputControl::uniform() const {
  return std::all_of(items.begin(), items.end(),
                     [](const std::vector<OutputSpec>& v) { return v.empty(); });
}

OutputControl output_control_of(const OutputFrequency& f) {
  if (f.every >= -1) return OutputControl{f.every, {}};
  Registry& r = registry();
  std::lock_guard<std::mutex> lock(r.mutex);
  const auto index = static_cast<std::size_t>(-f.every - 2);
  IMPACTFE_CHECK(index < r.controls.size(), "unknown output-control code");
  return r.controls[index];
}

OutputFrequency output_frequency_of(const OutputControl& control) {
  OutputFrequency f;
  if (control.uniform()) {
    f.every = control.every;
    return f;
  }
  Registry& r = registry();
  std::lock_guard<std::mutex> lock(r.mutex);
  r.controls.push_back(control);
  f.every = -static_cast<int>(r.controls.size()) - 1;  // index 0 -> -2
  return f;
}

}  // namespace impactfe
