#pragma once
/// OUTRES per item, frequency and component (APDL_SCRIPTING §E.8): which results one substep
/// writes, and the masking of a time point to them. Items not written at a stored point are NaN
/// there ("absent", docs/results_file.md "Output control (OUTRES)").
#include <array>
#include <string>
#include <vector>

#include "core/output_control.h"
#include "results/results_file.h"

namespace impactfe {

/// The nodes or elements an item is written for at one substep: every one except `exceptions`
/// when `base` is true, only `exceptions` otherwise.
struct IdSelection {
  bool base = false;
  std::vector<int> exceptions;  // ascending
  bool none() const { return !base && exceptions.empty(); }
  bool all() const { return base && exceptions.empty(); }
  bool contains(int id) const;
};

/// What one substep writes, item by item.
struct OutputSelection {
  std::array<IdSelection, kOutputItems> items;
  const IdSelection& operator[](OutputItem i) const { return items[static_cast<int>(i)]; }
  /// True when some item is written for some node or element: the point is stored.
  bool any() const;
  /// True when some element item (STRS, EPEL, MISC) is written.
  bool any_element_item() const;
};

/// The selection at substep k of a load step of n substeps; k = 0 is the initial state of a
/// transient, written for every item that is not NONE.
OutputSelection output_selection(const OutputControl& control, int substep, int n_substeps);

/// Automatic time stepping (docs/solution_control.md): a substep the step control took between
/// the requested times writes only the items of frequency ALL (every substep taken); the
/// requested times themselves (the nominal grid j·Δt₀, j a multiple of a frequency n > 1, and
/// the load-step end) use output_selection with the grid index j.
OutputSelection output_selection_between(const OutputControl& control);
/// Substeps of a load step of `n_substeps` constant substeps that store a point, at most (the
/// initial state of a transient not counted): every one when some item is written at every
/// substep, else the multiples of each frequency n > 1 and the last.
long long stored_substeps_at_most(const OutputControl& control, int n_substeps);

/// The OUTRES frequencies n > 1 of a load step (the strides of its requested times).
std::vector<int> output_strides(const OutputControl& control);

/// OUTRES item of an element result column, by its name: EPEL... → EPEL; stresses (SX.., SY..,
/// SZ.., S1 S2 S3, SINT, SEQV.., SAXL) → STRS; everything else (forces, moments per length,
/// status, deflections, lengths) → MISC.
OutputItem element_item_category(const std::string& item_name);

/// Sets what the selection does not write to NaN (rows of nodes, element rows per column
/// category); a quantity written for nothing is emptied (absent). `node_ids`: the rows of the
/// nodal tables (ascending node ids).
void apply_output_selection(const OutputSelection& s, const std::vector<int>& node_ids,
                            TimePoint& p);

/// OUTRES,STAT: one line per item, e.g. "NSOL  every 5 substeps and the last for all".
std::vector<std::string> describe_output(const OutputControl& control);

/// Name of an item as OUTRES,STAT lists it: "NSOL", "V", "A", "RSOL", "STRS", "EPEL", "MISC".
const char* output_item_name(OutputItem item);

}  // namespace impactfe
