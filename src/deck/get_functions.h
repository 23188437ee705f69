#pragma once
/// The results group of the get functions (APDL_MODELING §10.3): UX..ROTZ, VX..VZ, AX..AZ of a
/// node in the current POST1 set. The model and selection group (NX, NODE(x,y,z), NSEL, ...) is
/// get_hooks.cpp's; both are registered in its table, so expressions reach them all.
#include <vector>

#include "deck/get_hooks.h"

namespace impactfe::deck {

void register_results_get_functions(std::vector<GetFunctionSpec>& table);

}  // namespace impactfe::deck
