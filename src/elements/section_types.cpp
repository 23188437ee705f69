#include "elements/section_types.h"

#include <fmt/format.h>

#include <algorithm>
#include <stdexcept>

#include "elements/beam_section.h"

namespace impactfe {

namespace {

/// A section of one homogeneous layer given by its first SECDATA value (`what`: the area of a
/// link, the thickness of a shell), which must be positive.
std::function<std::string(const Section&)> positive_first_value(const char* what) {
  return [what](const Section& s) -> std::string {
    if (s.data.empty() || s.data[0] <= 0.0)
      throw std::invalid_argument(fmt::format("{} must be positive", what));
    return {};
  };
}

const std::vector<SectionTypeDescriptor>& section_types() {
  static const std::vector<SectionTypeDescriptor> types = {
      {.name = "LINK", .single_secdata = true, .check_data = positive_first_value("area")},
      // Shells: the section's reference plane is the middle surface (MID).
      {.name = "SHELL",
       .offsets = {"MID"},
       .single_secdata = true,
       .check_data = positive_first_value("thickness")},
      // 2-D solids (PLANE182/183 KEYOPT(3) = 3): the thickness.
      {.name = "PLANE", .single_secdata = true, .check_data = positive_first_value("thickness")},
      // Beams: the subtype's dimensions (at most 12 values), whose properties go to the log;
      // the nodes lie on the centroid (CENT), the only placement impactfe computes.
      {.name = "BEAM",
       .subtypes = beam_section_subtypes(),
       .offsets = {"CENT"},
       .max_values = 12,
       .check_data = [](const Section& s) {
         return fmt::format("beam section {} ({}): {}", s.id, s.subtype,
                            describe_beam_section(beam_section_properties(s.subtype, s.data)));
       }}};
  return types;
}

std::string joined(const std::vector<std::string>& names, const char* last_separator) {
  if (names.empty()) return "none";
  std::string out;
  for (std::size_t k = 0; k < names.size(); ++k)
    out += (k == 0 ? "" : k + 1 == names.size() ? last_separator : ", ") + names[k];
  return out;
}

}  // namespace

bool SectionTypeDescriptor::accepts_subtype(const std::string& subtype) const {
  return std::find(subtypes.begin(), subtypes.end(), subtype) != subtypes.end();
}

std::string SectionTypeDescriptor::subtype_names() const {
  return joined(subtypes, ", ");
}

std::string SectionTypeDescriptor::offset_names() const {
  return joined(offsets, ", ");
}

const SectionTypeDescriptor* find_section_type(const std::string& name) {
  for (const auto& t : section_types())
    if (t.name == name) return &t;
  return nullptr;
}

std::string supported_section_type_names() {
  std::vector<std::string> names;
  for (const auto& t : section_types()) names.push_back(t.name);
  return joined(names, " or ");
}

}  // namespace impactfe
