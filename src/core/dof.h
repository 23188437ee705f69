#pragma once
/// Nodal degrees of freedom: three translations and three rotations, in nodal axes.
#include <array>
#include <compare>
#include <optional>
#include <string>
#include <string_view>

namespace impactfe {

enum class Dof : int { UX = 0, UY = 1, UZ = 2, ROTX = 3, ROTY = 4, ROTZ = 5 };
inline constexpr int kDofsPerNode = 6;
inline constexpr std::array<Dof, 6> kAllDofs = {Dof::UX,   Dof::UY,   Dof::UZ,
                                                Dof::ROTX, Dof::ROTY, Dof::ROTZ};

/// "UX".."ROTZ".
const char* dof_name(Dof dof);
/// Parses a displacement label (UX..ROTZ, case-insensitive); nullopt otherwise.
std::optional<Dof> parse_dof_label(std::string_view label);
/// Parses a force label (FX FY FZ MX MY MZ) to the DOF it acts on; nullopt otherwise.
std::optional<Dof> parse_force_label(std::string_view label);
/// Force label of a DOF: FX..MZ.
const char* force_name(Dof dof);
inline bool is_rotation(Dof dof) {
  return static_cast<int>(dof) >= 3;
}

/// One nodal DOF identified by the user's node number.
struct DofKey {
  int node = 0;
  Dof dof = Dof::UX;
  auto operator<=>(const DofKey&) const = default;
};

/// "N12 UZ" for messages.
std::string describe(const DofKey& key);

}  // namespace impactfe
