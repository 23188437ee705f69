#pragma once
/// The fields each element type reads: its real constants by position and the KEYOPT values it
/// carries out (MAPDL's element input summaries, as implemented). Anything else that a deck
/// gives is refused when the element is built, so that no field is silently ignored or read
/// with the meaning of another element (a LINK180 real set read as LINK8's: ADDMAS taken for an
/// initial strain). Kept beside the registry (element_registry.h), one entry per type, and
/// checked against it by ElementFields.EveryDeclaredFieldActs (tests/unit/test_element_fields.cpp).
#include <string>
#include <vector>

#include "core/model.h"

namespace impactfe {

/// Real constant `position` (1-based) of an element type's set.
struct RealConstantField {
  int position = 0;
  std::string name;      // MAPDL's label: "AREA", "ADDMAS"
  bool refused = false;  // known to MAPDL, not implemented: a nonzero value is refused
};

/// KEYOPT(number) and the values carried out (0, the default, always is).
struct KeyoptField {
  int number = 0;
  std::vector<int> values;
  std::string meaning;  // for messages and docs: "2: lumped mass (1)"
};

struct ElementFields {
  std::string type;  // ANSYS name
  std::vector<RealConstantField> real_constants;
  std::vector<KeyoptField> keyopts;
  /// The real set belongs to a contact pair and is checked by the contact element (TARGE170).
  bool real_set_of_pair = false;
};

/// The declared fields of a type (nullptr when the type has no entry: a test-only type).
const ElementFields* element_fields(const std::string& type);
/// Every entry, in name order.
const std::vector<ElementFields>& all_element_fields();

/// Why the KEYOPTs of `type` are refused ("" when every nonzero one is declared with its value).
std::string keyopt_refusal(const ElementType& type);
/// Why real set `set` is refused for an element of `type` that reads it ("" when every nonzero
/// value lies at a declared position that is not refused).
std::string real_set_refusal(const ElementType& type, const RealSet& set);

}  // namespace impactfe
