#pragma once
/// The section types of SECTYPE (APDL_MODELING §7.2) and what each says about itself: its
/// subtypes, its SECOFFSET locations and how its SECDATA values are read and checked. The deck
/// reader takes all of this from here; nothing outside src/elements tests a section's type.
#include <functional>
#include <string>
#include <vector>

#include "core/model.h"

namespace impactfe {

struct SectionTypeDescriptor {
  std::string name;  // SECTYPE Type, upper case: "BEAM"
  /// SECTYPE Subtype values accepted, the default (blank field) first; empty: the type takes
  /// none (the field is ignored).
  std::vector<std::string> subtypes;
  /// SECOFFSET locations accepted, the default (blank field) first; empty: none.
  std::vector<std::string> offsets;
  /// SECDATA values kept (0: every value given, at least one).
  int max_values = 0;
  /// A second SECDATA is refused (a single homogeneous layer); otherwise it replaces the data.
  bool single_secdata = false;
  /// Each SECDATA adds a layer (Section::layers) instead of replacing the data (SHELL).
  bool layered = false;
  /// Checks a section's SECDATA values: throws std::invalid_argument with the reason (a user
  /// message); returns a line for the log (empty: nothing to log).
  std::function<std::string(const Section&)> check_data;

  bool accepts_subtype(const std::string& subtype) const;
  /// "RECT, CSOLID, CTUBE, I, HREC, ASEC" (subtypes), "CENT" (offsets), "none" when empty.
  std::string subtype_names() const;
  std::string offset_names() const;
};

/// The section type named `name` (upper case), nullptr when unknown.
const SectionTypeDescriptor* find_section_type(const std::string& name);
/// "LINK, SHELL or BEAM" for error messages.
std::string supported_section_type_names();

}  // namespace impactfe
