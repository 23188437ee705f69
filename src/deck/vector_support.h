#pragma once
/// Shared machinery of the *V and *M commands (APDL_MODELING §10.2): operands (an array column
/// from a start element, a scalar parameter or a constant), the result column, and the
/// *VLEN / *VMASK / *VFACT / *VABS / *VCUM settings that apply to one operation and are reset.
/// Internal to the deck layer.
#include <cmath>
#include <string>
#include <vector>

#include "deck/deck_context.h"
#include "deck/get_hooks.h"

namespace impactfe::deck {

/// An input of a vector operation.
struct VectorOperand {
  bool column = false;
  ArrayPosition pos;      // column: start element
  double constant = 0.0;  // scalar parameter or constant
  /// Rows available from the start (a constant: unlimited).
  long long length() const { return column ? pos.param->imax - pos.i + 1 : -1; }
  /// Row `row` (0-based from the start), column offset `dj`.
  double at(long long row, int dj = 0) const;
};

/// Field `f` as an operand: an element of a numeric array (`A(1)`, `A(2,3)`, a bare array name =
/// its first element), or a number / scalar expression. Error for a blank required field.
VectorOperand vector_operand(DeckReader& r, const Command& c, int f);

/// One operation's settings, taken from r.scripting.vector_settings (which are then reset, §10.2).
struct VectorPass {
  std::string result;        // ParR as written
  ArrayPosition out;         // result start (created as a 1-D array when undefined)
  long long rows = 0;        // rows operated
  int step = 1;              // *VLEN NINC
  std::vector<char> active;  // *VMASK: row operated (1) or skipped (0)
  VectorSettings settings;

  /// Row `k` of the pass → row offset in the columns.
  long long row(long long k) const { return k * step; }
  /// Stores `value` at pass row k (factor FACTR, *VABS KABSR and *VCUM applied).
  void store(long long k, double value, int dj = 0) const;
  double in1(double v) const { return settings.factor1 * (settings.abs1 ? std::fabs(v) : v); }
  double in2(double v) const { return settings.factor2 * (settings.abs2 ? std::fabs(v) : v); }
  double in3(double v) const { return settings.factor3 * (settings.abs3 ? std::fabs(v) : v); }
};

/// Prepares a pass over `result` (field `f`): rows = *VLEN NROW, else the rest of the result
/// column, else `default_rows` (the input column) when the result array must be created with
/// `create_cols` columns.
VectorPass begin_vector_pass(DeckReader& r, const Command& c, int f, long long default_rows,
                             int create_cols = 1);

/// *MFUN, *MOPER, *VGET, *VPUT (matrix_commands.cpp), registered with the vector commands.
void register_matrix_commands(std::vector<CommandSpec>& table);

}  // namespace impactfe::deck
