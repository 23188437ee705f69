#pragma once
/// OUTRES per item, frequency and component (APDL_SCRIPTING §E.8) for a load step.
///
/// A load step carries its output frequency in `LoadStep::output.every` (core/model.h): n > 0
/// every n-th substep and the last, 0 the last substep, -1 none (OUTRES,ALL,NONE). When OUTRES
/// sets items one by one, `every` holds a code <= -2 naming an OutputControl registered here
/// (append-only, for the life of the process), so that the widely included model header stays
/// as it is. docs/results_file.md, "Output control (OUTRES)".
#include <array>
#include <string>
#include <vector>

#include "core/model.h"

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

/// The output settings of a load step: `every` for all items, and per item (when not empty)
/// its specifications in command order, a later one winning for the nodes / elements it covers.
struct OutputControl {
  int every = 0;
  std::array<std::vector<OutputSpec>, kOutputItems> items;
  /// True when no item has specifications of its own.
  bool uniform() const;
};

/// The settings a load step's output frequency stands for.
OutputControl output_control_of(const OutputFrequency& f);
/// The output frequency that stands for `control`: its `every` when uniform, else a code of
/// the registry.
OutputFrequency output_frequency_of(const OutputControl& control);

}  // namespace impactfe
