#pragma once
/// Deck-reading state of the model-building commands (APDL_MODELING §3-§6) that is not part of
/// the model itself: the MPTEMP temperature table and the TB table that TBTEMP/TBDATA/TBPT fill.
#include <optional>
#include <string>
#include <utility>
#include <vector>

namespace impactfe::deck {

struct ModelingState {
  std::vector<double> mptemp;  // MPTEMP temperatures (positions 1..)
  /// (MAT, Lab) of the last TB command and the index of its current temperature (TBTEMP).
  std::optional<std::pair<int, std::string>> table;
  std::size_t table_temperature = 0;
  int esys = 0;  // ESYS pointer
  /// TSHAP shape of the TARGE170 elements that E/EN define next ("" = from the node count).
  std::string target_shape;
};

}  // namespace impactfe::deck
