#pragma once
/// Fortran edit descriptors of the CDB blocks' format lines ("(3i9,6e21.13e3)", "(19i10)",
/// "(2i8,6g16.9)"): the width of each column, so that records are read by column as MAPDL
/// writes them (numbers may touch: "0-2.87E-001-7.73E-001").
#include <string_view>
#include <vector>

namespace impactfe::deck {

struct FortranField {
  char kind = 'I';  // I (integer), E/G/F/D (real), X (blanks), A (text)
  int count = 1;
  int width = 0;
};

/// The descriptors of a format line; throws std::invalid_argument naming what it cannot read.
std::vector<FortranField> parse_fortran_format(std::string_view format);

/// One width per column (repeat counts expanded; X columns kept as columns).
std::vector<int> field_widths(const std::vector<FortranField>& fields);

}  // namespace impactfe::deck
