#pragma once
/// TEMPORARY stand-in for the language half of issue 9 (branch `lang`: parameters, arrays,
/// *VWRITE, the output sink). It implements the four contract functions the post-processing
/// code is written against, an output function, and the few array commands the verification
/// decks need (*DIM, *VFILL DATA/RAMP, *VOPER, *VWRITE with a Fortran format, *CFOPEN,
/// *CFCLOS), minimally. The lead deletes language_standin.h/.cpp when `lang` merges and points
/// deck/post_support.h at deck/parameters.h and the real output sink.
#include <optional>
#include <string>
#include <vector>

#include "deck/deck_context.h"

namespace impactfe::deck {

/// target "NAME" or "NAME(i[,j[,k]])".
void assign_parameter(DeckReader& r, const Command& c, const std::string& target, double value);
void assign_text_parameter(DeckReader& r, const Command& c, const std::string& target,
                           const std::string& value);
/// As *VGET fills an array column: target "NAME" or "NAME(i[,j])"; created when absent.
void assign_vector(DeckReader& r, const Command& c, const std::string& target,
                   const std::vector<double>& values);
/// As *VPUT reads one: `count` values from source "NAME(i[,j])" down its column.
std::vector<double> read_vector(DeckReader& r, const Command& c, const std::string& source,
                                int count);

/// The output sink (standard output, or the /OUT file once the language branch has it).
void write_output(DeckReader& r, const std::string& text);

/// *GET,Par,PARM,Name,TYPE / DIM: type code (-1 undefined, 0 numeric scalar, 1 numeric array,
/// 3 character scalar, 4 character array) and extents.
struct ParameterInfo {
  int type = -1;
  int dims[3] = {0, 0, 0};
};
ParameterInfo parameter_info(DeckReader& r, const std::string& name);
/// Number of defined parameters (PARM,,MAX) and of numeric scalars (PARM,,BASIC).
std::pair<int, int> parameter_counts(DeckReader& r);

void register_language_standin_commands(std::vector<CommandSpec>& table);
/// *VWRITE with the deck line after it as its Fortran format (run by the executor).
void standin_vwrite(DeckReader& r, const Command& c, const std::string& format_line);

}  // namespace impactfe::deck
