#pragma once
/// The contact summary of a load step (like MAPDL's CONTSTAT): over the elements that report the
/// contact results STAT, FN and PENE (CONTA175, CONTA178: elements/contact_point.h), the number
/// in contact, the number sliding, the largest penetration and the total normal force.
#include <memory>
#include <optional>
#include <string>
#include <vector>

#include "assembly/assembler.h"
#include "elements/element.h"

namespace impactfe {

/// One log line for the state u (all active DOFs) at the end of load step `load_step` (time t);
/// nullopt when the model has no contact elements.
std::optional<std::string> contact_summary(const std::vector<std::unique_ptr<Element>>& elements,
                                           const Assembler& assembler, const VectorXd& u,
                                           int load_step, double time);

}  // namespace impactfe
