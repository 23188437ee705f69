// The beam element types on the Beam kernel (elements/beam.h): BEAM188 with a SECTYPE,,BEAM
// section (APDL_MODELING §8.1), and the 4.2-era elastic beams BEAM4 (3-D) and BEAM3 (2-D, X-Y
// plane) with their real constants (§8.2).
#include <fmt/format.h>

#include <Eigen/Geometry>

#include <cmath>
#include <stdexcept>

#include "core/log.h"
#include "elements/beam.h"
#include "elements/beam_setup.h"
#include "elements/element_registry.h"
#include "elements/line_element_data.h"
#include "materials/linear_elastic.h"

namespace impactfe {

namespace {

/// Nodes, frame, material and DOFs common to the three types; the section is filled by the
/// caller. `planar` (BEAM3): X-Y plane, z = global Z, DOFs UX, UY, ROTZ.
BeamData beam_data(const Model& model, const ElementRecord& record, const char* name, bool planar,
                   double theta_deg) {
  const auto [ni, nj] = line_data::distinct_node_pair(model, record, name);
  BeamData d;
  d.node_i = ni.id;
  d.node_j = nj.id;
  d.xi = ni.x;
  d.xj = nj.x;
  const double L = (nj.x - ni.x).norm();
  if (!(L > 0.0))
    throw beam_element_error(record, name,
                             fmt::format("zero length (nodes {} and {} coincide)", ni.id, nj.id));
  if (planar) {
    if (std::abs(nj.x.z() - ni.x.z()) > 1e-9 * L)
      throw beam_element_error(record, name, "BEAM3 must lie in an X-Y plane (nodes differ in Z)");
    if (record.nodes.size() > 2)
      throw beam_element_error(record, name, "BEAM3 has nodes I, J only");
    const Vec3 ex = (nj.x - ni.x) / L;
    d.frame.col(0) = ex;
    d.frame.col(2) = Vec3::UnitZ();
    d.frame.col(1) = Vec3::UnitZ().cross(ex);
    d.active = {0, 1, 5, 6, 7, 11};
  } else {
    const Vec3* xk = nullptr;
    if (record.nodes.size() > 2 && record.nodes[2] > 0) {
      const Node& nk = line_data::node(model, record, 2, 3, name);
      xk = &nk.x;
      if (theta_deg != 0.0)
        Log::warn("element {} ({}): THETA = {} ignored: the orientation node K sets the axes",
                  record.id, name, theta_deg);
    }
    d.frame = beam_frame(record, name, ni.x, nj.x, xk, theta_deg);
    d.active = {0, 1, 2, 3, 4, 5, 6, 7, 8, 9, 10, 11};
  }
  const ElasticMaterial mat = elastic_material(model, record, name);
  d.youngs_modulus = mat.youngs_modulus;
  d.shear_modulus = mat.youngs_modulus / (2.0 * (1.0 + mat.poisson_ratio));
  d.density = mat.density;
  return d;
}

std::unique_ptr<Element> make_beam188(const ElementBuildContext& ctx, const ElementRecord& record) {
  const Model& model = ctx.model;
  const char* name = "BEAM188";
  const ElementType& type = line_data::element_type(model, record);
  if (type.key(1) != 0)
    throw beam_element_error(record, name,
                             "KEYOPT(1) = 1 (warping DOF) is not supported (APDL_MODELING §8.1)");
  if (type.key(3) != 0 && type.key(3) != 2 && type.key(3) != 3)
    throw beam_element_error(
        record, name,
        fmt::format("KEYOPT(3) = {} is not a valid interpolation (0, 2 or 3)", type.key(3)));
  BeamData d = beam_data(model, record, name, false, 0.0);
  const double nu = d.youngs_modulus / (2.0 * d.shear_modulus) - 1.0;
  d.section = record_beam_section(model, record, name, nu, d.shear_modulus);
  d.added_mass = d.section.added_mass;
  // TB plasticity: a law per fibre of the section (docs/plasticity.md). ASEC has properties but
  // no geometry, so there is nothing to integrate the stresses over (its 4 fibres only reproduce
  // A and the second moments): refused rather than yielding at made-up points.
  d.plasticity = plasticity_of(model, record, d.youngs_modulus, nu);
  if (d.plasticity && d.section.subtype == "ASEC")
    throw beam_element_error(
        record, name,
        fmt::format("section {} is ASEC (properties only, no geometry to integrate stresses over): "
                    "material {} has a TB plasticity table, which BEAM188 supports only for the "
                    "RECT, CSOLID, CTUBE, I and HREC subtypes",
                    record.secnum, record.mat));
  return std::make_unique<Beam>(record.id, std::move(d));
}

/// BEAM4 / BEAM3 section from the real constants, as an ASEC-like property section.
BeamSectionProperties legacy_section(const ElementRecord& record, const char* name, double area,
                                     double izz, double iyy, double ixx, double tkz, double tky,
                                     double shearz, double sheary) {
  if (!(area > 0.0)) throw beam_element_error(record, name, "AREA is missing or not positive");
  if (!(izz > 0.0)) throw beam_element_error(record, name, "IZZ is missing or not positive");
  if (!(iyy > 0.0)) throw beam_element_error(record, name, "IYY is missing or not positive");
  if (tkz < 0.0 || tky < 0.0 || shearz < 0.0 || sheary < 0.0)
    throw beam_element_error(record, name, "TKZ, TKY, SHEARZ and SHEARY must not be negative");
  BeamSectionProperties p =
      beam_section_properties("ASEC", {area, iyy, 0.0, izz, 0.0, ixx, 0, 0, 0, 0, tkz, tky});
  // Shear deflection constants A/As; 0 = no shear deformation.
  p.shear_area_z = shearz > 0.0 ? area / shearz : 0.0;
  p.shear_area_y = sheary > 0.0 ? area / sheary : 0.0;
  return p;
}

std::unique_ptr<Element> make_beam4(const ElementBuildContext& ctx, const ElementRecord& record) {
  const Model& model = ctx.model;
  const char* name = "BEAM4";
  const RealSet& rs = line_data::real_set(model, record, name);
  const ElementType& type = line_data::element_type(model, record);
  // AREA, IZZ, IYY, TKZ, TKY, THETA; ISTRN, IXX, SHEARZ, SHEARY, SPIN, ADDMAS.
  if (rs.get(11) != 0.0)
    throw beam_element_error(record, name, "SPIN (real constant 11) is not supported");
  BeamData d = beam_data(model, record, name, false, rs.get(6));
  const double ixx = rs.get(8) != 0.0 ? rs.get(8) : rs.get(2) + rs.get(3);
  d.section = legacy_section(record, name, rs.get(1), rs.get(2), rs.get(3), ixx, rs.get(4),
                             rs.get(5), rs.get(9), rs.get(10));
  d.initial_strain = rs.get(7);
  d.added_mass = rs.get(12);
  d.lumped_mass = type.key(2) == 1;
  return std::make_unique<Beam>(record.id, std::move(d));
}

std::unique_ptr<Element> make_beam3(const ElementBuildContext& ctx, const ElementRecord& record) {
  const Model& model = ctx.model;
  const char* name = "BEAM3";
  const RealSet& rs = line_data::real_set(model, record, name);
  const ElementType& type = line_data::element_type(model, record);
  // AREA, IZZ, HEIGHT, SHEARZ, ISTRN, ADDMAS. The out-of-plane properties are not used (their
  // DOFs are not the element's); IYY = J = IZZ keep the section valid.
  BeamData d = beam_data(model, record, name, true, 0.0);
  const double izz = rs.get(2);
  d.section =
      legacy_section(record, name, rs.get(1), izz, izz, izz, 0.0, rs.get(3), 0.0, rs.get(4));
  d.initial_strain = rs.get(5);
  d.added_mass = rs.get(6);
  d.lumped_mass = type.key(2) == 1;
  return std::make_unique<Beam>(record.id, std::move(d));
}

std::vector<ResultSequence> concat(std::initializer_list<std::vector<ResultSequence>> parts) {
  std::vector<ResultSequence> all;
  for (const auto& p : parts) all.insert(all.end(), p.begin(), p.end());
  return all;
}

// The pressure faces (SFBEAM, SFE; Beam::pressure_load): BEAM188 and BEAM4 1-3 along I-J
// (−z, −y normal; +x tangential), 4 at I, 5 at J (axial); BEAM3 1-2 along I-J, 3 at I, 4 at J.
// SF by selected nodes loads none of them (sf_faces 0), as in MAPDL.
const std::vector<std::vector<int>> kBeamFaces = {{0, 1}, {0, 1}, {0, 1}, {0}, {1}};
const std::vector<std::vector<int>> kPlanarBeamFaces = {{0, 1}, {0, 1}, {0}, {1}};

// APDL_MODELING §8.1: SMISC 1-6 / 14-19 FX MY MZ TQ SFZ SFY at I / J; 31-35 / 36-40 SDIR SByT
// SByB SBzT SBzB at I / J.
const ElementRegistration kBeam188{
    {.name = "BEAM188",
     .number = 188,
     .family = "Beam",
     .n_nodes = 2,
     .n_optional_nodes = 1,
     .real_constants = RealConstantUse::None,
     .needs_material = true,
     .section_types = {"BEAM"},
     .vtk_cell = VtkCell::Line,
     .role = ShapeRole::Line,
     .result_names = beam_result_names(),
     .result_sequences = concat(
         {numbered_sequences("SMISC", 1, {"FX_I", "MY_I", "MZ_I", "TQ_I", "SFZ_I", "SFY_I"}),
          numbered_sequences("SMISC", 14, {"FX_J", "MY_J", "MZ_J", "TQ_J", "SFZ_J", "SFY_J"}),
          numbered_sequences("SMISC", 31,
                             {"SDIR_I", "SBYT_I", "SBYB_I", "SBZT_I", "SBZB_I", "SDIR_J", "SBYT_J",
                              "SBYB_J", "SBZT_J", "SBZB_J"}),
          {{"NL", "EPEQ", "EPEQ"}, {"NL", "SRAT", "SRAT"}, {"NL", "PLWK", "PLWK"}}}),
     .plasticity = true,
     .faces = kBeamFaces,
     .note = "BEAM188: KEYOPT(3) = 0, 2, 3 give one element (exact stiffness for nodal loads, "
             "cubic mass); KEYOPT(2) not used (rigid cross section under NLGEOM)",
     .create = make_beam188}};

// APDL_MODELING §8.2 (BEAM4): LS 1-5 / 6-10 SDIR SBYT SBYB SBZT SBZB at I / J; NMISC 1-4 SMAX(I)
// SMIN(I) SMAX(J) SMIN(J); SMISC 1-6 / 7-12 MFORX MFORY MFORZ MMOMX MMOMY MMOMZ at I / J.
const ElementRegistration kBeam4{
    {.name = "BEAM4",
     .number = 4,
     .family = "Beam",
     .n_nodes = 2,
     .n_optional_nodes = 1,
     .real_constants = RealConstantUse::Required,
     .needs_material = true,
     .vtk_cell = VtkCell::Line,
     .role = ShapeRole::Line,
     .result_names = beam_result_names(),
     .result_sequences =
         concat({numbered_sequences("LS", 1,
                                    {"SDIR_I", "SBYT_I", "SBYB_I", "SBZT_I", "SBZB_I", "SDIR_J",
                                     "SBYT_J", "SBYB_J", "SBZT_J", "SBZB_J"}),
                 numbered_sequences("NMISC", 1, {"SMAX_I", "SMIN_I", "SMAX_J", "SMIN_J"}),
                 numbered_sequences("SMISC", 1,
                                    {"FX_I", "SFY_I", "SFZ_I", "TQ_I", "MY_I", "MZ_I", "FX_J",
                                     "SFY_J", "SFZ_J", "TQ_J", "MY_J", "MZ_J"})}),
     .faces = kBeamFaces,
     .create = make_beam4}};

// BEAM3: LS 1-3 / 4-6 SDIR SBYT SBYB at I / J; NMISC 1-4; SMISC 1, 2, 6 / 7, 8, 12 MFORX MFORY
// MMOMZ at I / J.
const ElementRegistration kBeam3{
    {.name = "BEAM3",
     .number = 3,
     .family = "Beam",
     .n_nodes = 2,
     .real_constants = RealConstantUse::Required,
     .needs_material = true,
     .vtk_cell = VtkCell::Line,
     .role = ShapeRole::Line,
     .result_names = beam_result_names(),
     .result_sequences = concat(
         {numbered_sequences("LS", 1, {"SDIR_I", "SBYT_I", "SBYB_I", "SDIR_J", "SBYT_J", "SBYB_J"}),
          numbered_sequences("NMISC", 1, {"SMAX_I", "SMIN_I", "SMAX_J", "SMIN_J"}),
          numbered_sequences(
              "SMISC", 1,
              {"FX_I", "SFY_I", "", "", "", "MZ_I", "FX_J", "SFY_J", "", "", "", "MZ_J"})}),
     .faces = kPlanarBeamFaces,
     .create = make_beam3}};

}  // namespace

}  // namespace impactfe
