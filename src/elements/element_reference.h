#pragma once
/// The element reference, generated from the registry (element_registry.h) and the declared
/// fields (element_fields.h): nodes, cell and role, required data, the real constants read (and
/// refused), the KEYOPT values carried out, sections, plasticity, surface loads and result items.
/// `impactfe help ELEMENT` prints an entry; docs/reference.md holds them all.
#include <string>

#include "elements/element_registry.h"

namespace impactfe {

/// One element type's entry (Markdown that reads as plain text).
std::string element_help(const ElementTypeDescriptor& type);
/// Every registered type, in name order, under a "## Elements" heading.
std::string element_reference_markdown();

}  // namespace impactfe
