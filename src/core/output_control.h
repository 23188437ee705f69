#pragma once
/// OUTRES per item, frequency and component (APDL_SCRIPTING §E.8): the output settings a load
/// step carries by value (`LoadStep::output`, core/model.h), so that copies of a load step and
/// SAVE/RESUME keep them. docs/results_file.md, "Output control (OUTRES)".
#include <algorithm>
#include <array>
#include <string>
#include <vector>

namespace impactfe {

/// Result items OUTRES controls one by one, as impactfe stores them: NSOL displacements (U),
/// VSOL velocities (V), ASOL accelerations (A), RSOL reactions (R); STRS / EPEL / MISC the
/// stress, elastic-strain and other columns of the element results (ESOL sets all three).
enum class OutputItem { NSOL, VSOL, ASOL, RSOL, STRS, EPEL, MISC };
inline constexpr int kOutputItems = 7;

/// One OUTRES,Item,Freq,Cname specification: frequency (-1 NONE, 0 last substep, n every n-th
/// substep and the last) for every node / element, or only for those of a component.
struct OutputSpec {
  int every = 0;
  std::string component;  // upper-case CM name; empty = every node / element
  std::vector<int> ids;   // the component's node or element ids (ascending)
};

/// The output settings of a load step (ITER NPOST / OUTRES): `every` for all items (n > 0 every
/// n-th substep and the last, 0 the last substep, -1 none), and per item (when not empty) its
/// specifications in command order, a later one winning for the nodes / elements it covers.
struct OutputControl {
  int every = 0;
  std::array<std::vector<OutputSpec>, kOutputItems> items;
  /// True when no item has specifications of its own.
  bool uniform() const {
    return std::all_of(items.begin(), items.end(),
                       [](const std::vector<OutputSpec>& v) { return v.empty(); });
  }
};

}  // namespace impactfe
