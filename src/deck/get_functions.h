#pragma once
/// The get functions of expressions that need the model, the selection or the results
/// (APDL_MODELING §10.3): NX NY NZ, NODE(x,y,z), NNEAR, ENEARN, DISTND, CENTRX/Y/Z, NELEM,
/// UX..ROTZ / VX.. / AX.. of the current set, NSEL ESEL, NDNEXT ELNEXT. The expression
/// evaluator of the language branch calls this through its hook for get functions.
#include <optional>
#include <string>
#include <vector>

#include "deck/deck_context.h"

namespace impactfe::deck {

/// Value of get function `name` (upper case) with `args`; nullopt when `name` is not one of
/// these functions. A wrong argument count or an undefined entity is an error of `c`.
std::optional<double> model_get_function(DeckReader& r, const Command& c, const std::string& name,
                                         const std::vector<double>& args);

}  // namespace impactfe::deck
