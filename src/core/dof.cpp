#include "core/dof.h"
#include "core/text.h"

#include <fmt/format.h>

namespace impactfe {

namespace {
constexpr std::array<const char*, 6> kDofNames = {"UX", "UY", "UZ", "ROTX", "ROTY", "ROTZ"};
constexpr std::array<const char*, 6> kForceNames = {"FX", "FY", "FZ", "MX", "MY", "MZ"};

}  // namespace

const char* dof_name(Dof dof) {
  return kDofNames[static_cast<int>(dof)];
}
const char* force_name(Dof dof) {
  return kForceNames[static_cast<int>(dof)];
}

std::optional<Dof> parse_dof_label(std::string_view label) {
  const std::string u = to_upper(label);
  for (int i = 0; i < 6; ++i)
    if (u == kDofNames[i]) return static_cast<Dof>(i);
  return std::nullopt;
}

std::optional<Dof> parse_force_label(std::string_view label) {
  const std::string u = to_upper(label);
  for (int i = 0; i < 6; ++i)
    if (u == kForceNames[i]) return static_cast<Dof>(i);
  return std::nullopt;
}

std::string describe(const DofKey& key) {
  return fmt::format("node {} {}", key.node, dof_name(key.dof));
}

}  // namespace impactfe
