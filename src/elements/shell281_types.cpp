// SHELL281 (shell281.h): the factory that reads the model and the registration.
#include <fmt/format.h>

#include <array>
#include <set>
#include <stdexcept>

#include "core/errors.h"
#include "elements/element_registry.h"
#include "elements/shell281.h"
#include "elements/shell_laminate.h"
#include "materials/isotropic_elasticity.h"
#include "materials/j2_plasticity.h"

namespace impactfe {

namespace {

std::unique_ptr<Element> make_shell281(const ElementBuildContext& ctx,
                                       const ElementRecord& record) {
  const Model& model = ctx.model;
  const auto fail = [&](const std::string& msg) {
    return InputError(record.where, fmt::format("element {} (SHELL281): {}", record.id, msg));
  };
  if (ctx.large_deflection)
    throw fail("large deflection (NLGEOM,ON) is not implemented for SHELL281; use SHELL181");
  const ElementType& type = model.element_types.at(record.type);
  const std::vector<int>& n = record.nodes;
  if (n.size() != 8) throw fail(fmt::format("needs 8 nodes I..P, got {}", n.size()));
  for (std::size_t k = 0; k < n.size(); ++k)
    if (n[k] == 0)
      throw fail(fmt::format("node {} is not given: midside nodes may not be omitted", k + 1));
  Shell281Data data;
  std::vector<int> corners_of;  // record positions of the element's nodes
  if (n[2] == n[3] && n[6] == n[2]) {
    // The triangle K = L = O: I J K with midsides M N P.
    corners_of = {0, 1, 2, 4, 5, 7};
  } else {
    corners_of = {0, 1, 2, 3, 4, 5, 6, 7};
  }
  for (int k : corners_of) data.node_ids.push_back(n[static_cast<std::size_t>(k)]);
  if (std::set<int>(data.node_ids.begin(), data.node_ids.end()).size() != data.node_ids.size())
    throw fail("repeated nodes are taken only as the triangle K = L = O");
  for (int id : data.node_ids) {
    const auto it = model.nodes.find(id);
    if (it == model.nodes.end()) throw fail(fmt::format("node {} is not defined", id));
    data.positions.push_back(it->second.x);
  }
  // Thickness: the section (SECTYPE SHELL / SECDATA, one per layer) or the real constants
  // TK(I..L); a midside node takes the mean of its corners.
  std::array<double, 4> tc{};
  const auto sec_it = model.sections.find(record.secnum);
  const bool by_section =
      record.secnum > 0 && sec_it != model.sections.end() && !sec_it->second.data.empty();
  int mat_id = record.mat;
  std::vector<shell::LayerInput> layers;
  if (by_section) {
    try {
      layers = shell::section_layers(model, sec_it->second, record.mat);
    } catch (const std::invalid_argument& e) {
      throw fail(e.what());
    }
    mat_id = layers.front().material;
    const std::string& offset = sec_it->second.offset;
    data.offset = offset == "BOT" ? 1.0 : offset == "TOP" ? -1.0 : 0.0;
  }
  const auto mat_it = model.materials.find(mat_id);
  if (mat_it == model.materials.end() || !mat_it->second.has("EX"))
    throw fail(fmt::format("material {} has no EX", mat_id));
  const Material& mat = mat_it->second;
  // One isotropic layer: E and ν; several layers or an orthotropic one: the laminate.
  const bool laminate =
      layers.size() > 1 || (layers.size() == 1 && !layers[0].elasticity.isotropic);
  if (!laminate) require_isotropic(mat, mat_id, record.id, record.where);
  data.E = mat.get("EX", 0.0);
  if (!(data.E > 0.0)) throw fail(fmt::format("material {}: EX must be positive", mat_id));
  data.nu = mat.has("NUXY") ? mat.get("NUXY", 0.3) : mat.get("PRXY", 0.3);
  data.rho = mat.get("DENS", 0.0);
  if (laminate) {
    data.laminate = shell::make_laminate(layers, data.shear_factor);
    tc.fill(data.laminate.thickness);
  } else if (by_section) {
    tc.fill(sec_it->second.data[0]);
  } else {
    const auto it = model.real_sets.find(record.real);
    if (it == model.real_sets.end())
      throw fail(fmt::format("no section {} and no real constant set {} (thickness)", record.secnum,
                             record.real));
    const double ti = it->second.get(1);
    for (int i = 0; i < 4; ++i) {
      const double t = it->second.get(i + 1);
      tc[static_cast<std::size_t>(i)] = t != 0.0 ? t : ti;
    }
  }
  const int nc = data.node_ids.size() == 8 ? 4 : 3;
  for (int i = 0; i < nc; ++i) {
    if (!(tc[static_cast<std::size_t>(i)] > 0.0)) throw fail("zero or negative thickness");
    data.thickness.push_back(tc[static_cast<std::size_t>(i)]);
  }
  for (int i = 0; i < nc; ++i)
    data.thickness.push_back(
        0.5 * (tc[static_cast<std::size_t>(i)] + tc[static_cast<std::size_t>((i + 1) % nc)]));
  data.membrane_only = type.key(1) == 1;
  // TB plasticity or implicit creep of a homogeneous isotropic section (as SHELL181's).
  data.plasticity = plasticity_of(model, record, data.E, data.nu);
  if (data.plasticity && laminate)
    throw fail("plasticity or creep (TB) with a layered or orthotropic section is not implemented");
  if (data.plasticity && data.membrane_only)
    throw fail("plasticity or creep (TB) with KEYOPT(1) = 1 (membrane only) is not implemented");
  if (record.esys != 0) {
    if (const std::string why = esys_refusal(model, record); !why.empty()) throw fail(why);
    // A curvilinear system's axes at the corners' centroid.
    Vec3 centroid = Vec3::Zero();
    for (int a = 0; a < nc; ++a) centroid += data.positions[static_cast<std::size_t>(a)] / nc;
    data.esys_axes = esys_axes_at(model, record.esys, centroid);
  }
  return std::make_unique<Shell281>(record.id, data, record.where);
}

const ElementRegistration kShell281{
    {.name = "SHELL281",
     .number = 281,
     .family = "Shell281",
     .n_nodes = 8,
     .real_constants = RealConstantUse::UnlessSection,
     .needs_material = true,
     .section_types = {"SHELL"},
     .vtk_cell = VtkCell::QuadraticQuad,
     .role = ShapeRole::Shell,
     // The layered element's names extend the homogeneous one's (the same columns first).
     .result_names = Shell281::layered_names(),
     // S and EPEL at the top surface (MAPDL's default; SHELL,MID / BOT choose the others);
     // SMISC 1-8 = N, M and Q resultants.
     .result_sequences =
         {{"S", "X", "SX_TOP"},       {"S", "Y", "SY_TOP"},     {"S", "XY", "SXY_TOP"},
          {"S", "EQV", "SEQV_TOP"},   {"EPEL", "X", "EPX_TOP"}, {"EPEL", "Y", "EPY_TOP"},
          {"EPEL", "XY", "EPXY_TOP"}, {"SMISC", "1", "TX"},     {"SMISC", "2", "TY"},
          {"SMISC", "3", "TXY"},      {"SMISC", "4", "MX"},     {"SMISC", "5", "MY"},
          {"SMISC", "6", "MXY"},      {"SMISC", "7", "QXZ"},    {"SMISC", "8", "QYZ"},
          {"NL", "EPEQ", "EPEQ"},     {"NL", "PLWK", "PLWK"},   {"NL", "CREQ", "CREQ"},
          {"EPCR", "X", "EPCRX"},     {"EPCR", "Y", "EPCRY"},   {"EPCR", "Z", "EPCRZ"},
          {"EPCR", "XY", "EPCRXY"},   {"EPCR", "YZ", "EPCRYZ"}, {"EPCR", "XZ", "EPCRXZ"},
          {"EPCR", "EQV", "EPCREQV"}},
     .esys_axes = true,
     .plasticity = true,
     // Faces 1 and 2 (bottom, top: all eight nodes), edges 3..6 (J-I, K-J, L-K, I-L and their
     // midside nodes); SF loads face 1.
     .faces = {{0, 1, 2, 3, 4, 5, 6, 7},
               {0, 1, 2, 3, 4, 5, 6, 7},
               {1, 0, 4},
               {2, 1, 5},
               {3, 2, 6},
               {0, 3, 7}},
     .sf_faces = 1,
     .note = "SHELL281 is a degenerated-continuum Mindlin-Reissner shell: 3x3 Gauss with "
             "tied transverse shear, small deflection; KEYOPT(1) = 1 has translations only; "
             "J2 plasticity or implicit creep (TB) of a homogeneous section at 5 Lobatto "
             "points through the thickness",
     .create = make_shell281}};

}  // namespace

}  // namespace impactfe
