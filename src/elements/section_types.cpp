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
      // Shells: one SECDATA per layer, bottom first (Thickness, MAT, THETA, NUMPT; the layer
      // name is a label only). The nodes lie on the middle (MID), bottom or top surface;
      // SHELL181 takes MID only (its factory refuses the others).
      {.name = "SHELL",
       .offsets = {"MID", "BOT", "TOP"},
       .max_values = 4,
       .layered = true,
       .check_data = [](const Section& s) -> std::string {
         const std::vector<double>& layer = s.layers.empty() ? s.data : s.layers.back();
         if (layer.empty() || layer[0] <= 0.0)
           throw std::invalid_argument("thickness must be positive");
         if (layer.size() > 3 && layer[3] != 0.0 && (layer[3] < 1.0 || layer[3] > 9.0))
           throw std::invalid_argument(
               fmt::format("NUMPT {:g}: 1 to 9 integration points per layer", layer[3]));
         return {};
       }},
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
