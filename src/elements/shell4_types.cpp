// SHELL63 and SHELL181 (shell4.h): the factory that reads the model and the registrations.
#include <fmt/format.h>

#include <cmath>
#include <memory>
#include <stdexcept>

#include "core/errors.h"
#include "elements/element_registry.h"
#include "elements/shell4.h"
#include "elements/shell_frame.h"
#include "elements/shell_laminate.h"
#include "materials/isotropic_elasticity.h"
#include "materials/j2_plasticity.h"

namespace impactfe {

namespace {

// Faces 1 and 2 (bottom, top: pressures normal to the shell) and the edges 3..6 (J-I, K-J, L-K,
// I-L: in-plane edge pressures); SF loads face 1 only (sf_faces).
const std::vector<std::vector<int>> kShellFaces = {{0, 1, 2, 3}, {0, 1, 2, 3}, {1, 0},
                                                   {2, 1},       {3, 2},       {0, 3}};

/// SHELL63 (thin DK kernel), or SHELL181 (`shell181`: the Mindlin–Reissner kernel).
std::unique_ptr<Element> make_shell4(const ElementBuildContext& ctx, const ElementRecord& record,
                                     bool shell181) {
  const Model& model = ctx.model;
  const auto fail = [&](const std::string& msg) {
    return InputError(record.where, fmt::format("element {}: {}", record.id, msg));
  };
  const auto type_it = model.element_types.find(record.type);
  if (type_it == model.element_types.end())
    throw fail(fmt::format("element type {} is not defined", record.type));
  const ElementType& type = type_it->second;
  Shell4Data data;
  data.shell181 = shell181;
  data.keep_corotational_stiffness = ctx.large_deflection;

  // Nodes: I, J, K, L; K = L (or three nodes) gives the triangle.
  std::vector<int> ids = record.nodes;
  if (ids.size() == 4 && ids[2] == ids[3]) ids.pop_back();
  if (ids.size() != 3 && ids.size() != 4)
    throw fail(fmt::format("SHELL needs nodes I, J, K, L (K = L for a triangle), got {}",
                           record.nodes.size()));
  for (std::size_t i = 0; i < ids.size(); ++i)
    for (std::size_t j = i + 1; j < ids.size(); ++j)
      if (ids[i] == ids[j]) throw fail(fmt::format("zero area: node {} repeated", ids[i]));
  for (int id : ids) {
    const auto it = model.nodes.find(id);
    if (it == model.nodes.end()) throw fail(fmt::format("node {} is not defined", id));
    data.positions.push_back(it->second.x);
  }
  data.node_ids = ids;
  // ESYS: the angle about the normal from the facet's e1 (I-J, the axes the kernel works in)
  // to the local system's x axis projected on the facet. The layer angles and the result axes
  // (THETA) turn by it.
  double esys_angle_deg = 0.0;
  if (record.esys != 0) {
    if (const std::string why = esys_refusal(model, record); !why.empty()) throw fail(why);
    ShellCorners x(3, static_cast<Eigen::Index>(ids.size()));
    for (std::size_t a = 0; a < ids.size(); ++a)
      x.col(static_cast<Eigen::Index>(a)) = data.positions[a];
    const ShellFrame f = shell_frame(x, false);
    const Vec3 ex = shell_esys_x_axis(esys_axes_at(model, record.esys, f.c), f.e3());
    esys_angle_deg = std::atan2(ex.dot(f.e2()), ex.dot(f.e1())) * 180.0 / M_PI;
  }

  // A layered section (several SECDATA, or an orthotropic layer): SHELL181 takes a symmetric
  // laminate (shell_laminate.h); the material of the first layer gives E and ν otherwise.
  const auto sec_it = model.sections.find(record.secnum);
  const bool by_section =
      record.secnum > 0 && sec_it != model.sections.end() && !sec_it->second.data.empty();
  int mat_id = record.mat;
  std::shared_ptr<const shell::Laminate> laminate;
  if (by_section) {
    const Section& sec = sec_it->second;
    if (!sec.offset.empty() && sec.offset != "MID")
      throw fail(fmt::format("section {}: SECOFFSET,{} is implemented for SHELL281 only (MID here)",
                             sec.id, sec.offset));
    std::vector<shell::LayerInput> layers;
    try {
      layers = shell::section_layers(model, sec, record.mat);
    } catch (const std::invalid_argument& e) {
      throw fail(e.what());
    }
    mat_id = layers.front().material;
    for (shell::LayerInput& layer : layers) layer.theta_deg += esys_angle_deg;
    if (layers.size() > 1 || !layers.front().elasticity.isotropic) {
      if (!shell181)
        throw fail(
            fmt::format("section {}: layered or orthotropic sections are implemented for "
                        "SHELL181 and SHELL281",
                        sec.id));
      auto lam = std::make_shared<shell::Laminate>(shell::make_laminate(layers));
      if (lam->B.norm() > 1e-9 * lam->A.norm() * lam->thickness)
        throw fail(
            fmt::format("section {} is unsymmetric (membrane-bending coupling B ≠ 0): "
                        "implemented for SHELL281 only",
                        sec.id));
      if (static_cast<int>(lam->plies.size()) > Shell4::kMaxResultLayers)
        throw fail(fmt::format("section {}: {} layers; at most {} are carried out", sec.id,
                               lam->plies.size(), Shell4::kMaxResultLayers));
      laminate = std::move(lam);
    }
  }
  // Material.
  const auto mat_it = model.materials.find(mat_id);
  if (mat_it == model.materials.end() || !mat_it->second.has("EX"))
    throw fail(fmt::format("material {} has no EX", mat_id));
  const Material& mat = mat_it->second;
  if (!laminate) require_isotropic(mat, mat_id, record.id, record.where);
  shell::KernelData& k = data.kernel;
  k.E = mat.get("EX", 0.0);
  if (!(k.E > 0.0)) throw fail(fmt::format("material {}: EX must be positive", mat_id));
  k.nu = mat.has("NUXY") ? mat.get("NUXY", 0.3) : mat.get("PRXY", 0.3);
  k.rho = mat.get("DENS", 0.0);

  // Thickness: SHELL181 section (SECTYPE SHELL / SECDATA) or real constants TK(I..L).
  const RealSet* real = nullptr;
  if (const auto it = model.real_sets.find(record.real); it != model.real_sets.end())
    real = &it->second;
  if (laminate) {
    k.t.fill(laminate->thickness);
    k.rho = laminate->mass_per_area / laminate->thickness;  // the mean density
    k.laminate = laminate;
  } else if (by_section) {
    k.t.fill(sec_it->second.data[0]);
  } else {
    if (real == nullptr)
      throw fail(fmt::format("real constant set {} is not defined", record.real));
    const double ti = real->get(1);
    for (int i = 0; i < 4; ++i) {
      const double t = real->get(i + 1);
      k.t[static_cast<std::size_t>(i)] = t != 0.0 ? t : ti;
    }
    if (ids.size() == 3) k.t[2] = real->get(3) != 0.0 ? real->get(3) : ti;
  }
  for (std::size_t i = 0; i < ids.size(); ++i)
    if (!(k.t[i] > 0.0)) throw fail("zero or negative thickness");
  // The other real constants apply whenever the thickness comes from them (a modern deck's
  // elements carry SECNUM 1 whether or not a section 1 exists).
  if (real != nullptr && !by_section) {
    k.efs = real->get(5);
    data.theta_deg = real->get(6);  // THETA
    k.rmi = real->get(7) != 0.0 ? real->get(7) : 1.0;
    k.added_mass = real->get(19);
  }
  data.theta_deg += esys_angle_deg;
  k.membrane = type.key(1) != 2;
  k.bending = type.key(1) != 1;
  // SHELL63 KEYOPT(3) = 2 suppresses the extra shapes; SHELL181's KEYOPT(3) chooses reduced
  // (0) or full integration with incompatible modes (2): the kernel's extra shapes for both.
  k.extra_shapes = shell181 || type.key(3) != 2;
  // SHELL181 is a Mindlin–Reissner shell (MITC transverse shear, shell_kernel_mindlin.cpp);
  // SHELL63 keeps the thin DK kernel.
  k.mindlin = shell181;
  // SHELL181's drilling penalty at Hughes & Brezzi's γ = G t (drill_factor 1) rather than
  // SHELL63's 10⁻³ G t: the drilling modes' frequency goes as √(12 γ / (ρ t³)), and at 10⁻³
  // they fell among a thick plate's first bending modes (54 Hz for a 1 m steel plate).
  if (shell181) k.drill_factor = 1.0;
  k.rotary_inertia = type.key(7) != 1;
  // SHELL181 takes TB plasticity; SHELL63 is elastic (the SOLVE check refuses it there).
  if (shell181) data.plasticity = plasticity_of(model, record, k.E, k.nu);
  if (laminate && data.plasticity)
    throw fail("plasticity (TB) with a layered or orthotropic section is not implemented");
  return std::make_unique<Shell4>(record.id, data, record.where);
}

ElementTypeDescriptor shell_type(const char* name, int number, bool shell181) {
  return {.name = name,
          .number = number,
          .family = "Shell4",
          .n_nodes = 4,
          .min_nodes = 3,
          .real_constants = RealConstantUse::UnlessSection,
          .needs_material = true,
          .section_types = {"SHELL"},
          .vtk_cell = VtkCell::Quad,
          .role = ShapeRole::Shell,
          // SHELL181's layered elements add the layers' columns after the homogeneous ones.
          .result_names = shell181 ? Shell4::layered_names() : Shell4::names(),
          // S at the top surface (MAPDL's default shell location); SMISC 1-6 = T and M resultants.
          .result_sequences =
              {{"S", "X", "SX_TOP"},     {"S", "Y", "SY_TOP"},      {"S", "XY", "SXY_TOP"},
               {"S", "EQV", "SEQV_TOP"}, {"SMISC", "1", "TX"},      {"SMISC", "2", "TY"},
               {"SMISC", "3", "TXY"},    {"SMISC", "4", "MX"},      {"SMISC", "5", "MY"},
               {"SMISC", "6", "MXY"},    {"SMISC", "7", "QXZ"},     {"SMISC", "8", "QYZ"},
               {"NL", "EPEQ", "EPEQ"},   {"NL", "SRAT", "SRAT"},    {"NL", "PLWK", "PLWK"},
               {"NL", "CREQ", "CREQ"},   {"EPCR", "X", "EPCRX"},    {"EPCR", "Y", "EPCRY"},
               {"EPCR", "Z", "EPCRZ"},   {"EPCR", "XY", "EPCRXY"},  {"EPCR", "YZ", "EPCRYZ"},
               {"EPCR", "XZ", "EPCRXZ"}, {"EPCR", "EQV", "EPCREQV"}},
          .esys_axes = true,
          .plasticity = shell181,
          .faces = kShellFaces,
          .sf_faces = 1,
          .note = shell181
                      ? "SHELL181 is a Mindlin-Reissner shell: MITC4 / MITC3 transverse shear, "
                        "2x2 integration with incompatible membrane modes for KEYOPT(3) = 0 "
                        "and 2; layered J2 plasticity with a TB table"
                      : "",
          .create = [shell181](const ElementBuildContext& ctx, const ElementRecord& record) {
            return make_shell4(ctx, record, shell181);
          }};
}

const ElementRegistration kShell63{shell_type("SHELL63", 63, false)};
const ElementRegistration kShell181{shell_type("SHELL181", 181, true)};

}  // namespace

}  // namespace impactfe
