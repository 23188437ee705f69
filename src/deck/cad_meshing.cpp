#include "deck/cad_meshing.h"

#include <fmt/format.h>

#include <filesystem>

#include "core/errors.h"
#include "deck/deck_reader.h"
#include "elements/element_registry.h"
#include "geometry/mesh_quality.h"

namespace impactfe::deck {

Model mesh_cad_file(const CadMeshRequest& request) {
  const ElementTypeDescriptor* type = find_element_type(request.type);
  if (type == nullptr)
    throw InputError(SourceLocation{request.file, 0},
                     fmt::format("--type {}: unknown element type ({})", request.type,
                                 supported_element_type_names()));
  const std::filesystem::path cad = std::filesystem::absolute(request.file);
  const std::string ext = cad.extension().string();
  const std::string stem = (cad.parent_path() / cad.stem()).string();
  // The element type says what is meshed: a solid type the volumes, any other the areas.
  std::string text = fmt::format("/PREP7\nET,1,{}\nMP,EX,1,1\nMP,PRXY,1,0.3\n", request.type);
  if (type->accepts_section("SHELL")) text += "SECTYPE,1,SHELL\nSECDATA,1\n";
  text += fmt::format("IGESIN,'{}',{}\n", stem, ext.empty() ? "" : ext.substr(1));
  if (request.esize > 0.0) text += fmt::format("ESIZE,{}\n", request.esize);
  if (request.triangles) text += "MSHAPE,1,2D\n";
  text += type->role == ShapeRole::Solid ? "VMESH,ALL\n" : "AMESH,ALL\n";
  return read_deck_text(text, request.file, DeckOptions{}).model;
}

std::string mesh_quality_lines(const Model& model) {
  std::vector<int> elements;
  for (const auto& [id, e] : model.elements) elements.push_back(id);
  const geometry::MeshQuality q = geometry::mesh_quality(model, elements);
  if (q.measured == 0) return {};
  std::string out = fmt::format("quality: {}\n", geometry::describe(q));
  if (q.past_limits > 0)
    out += fmt::format(
        "quality: {} element(s) past the shape limits ({} inverted or flat), the first element "
        "{}\n",
        q.past_limits, q.inverted, q.first_past_limits);
  return out;
}

}  // namespace impactfe::deck
