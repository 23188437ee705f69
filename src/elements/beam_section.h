#pragma once
/// Beam cross sections (SECTYPE,,BEAM; APDL_MODELING §7.2): the section's properties (area,
/// second moments, torsion constant, shear areas, extreme fibres) and its integration points
/// (fibres: position y, z and area, relative to the centroid).
///
/// The axial-bending response of a beam section goes through the fibres: the section tangent
/// D = Σ_f E_t,f a_f g_f g_fᵀ with g_f = (1, z_f, −y_f) and the resultants (N, My, Mz) =
/// Σ_f σ_f a_f g_f, so a per-fibre uniaxial material law (plasticity) replaces the elastic one
/// without touching the element (Spacone, Filippou & Taucer 1996, EESD 25, the fibre section).
/// The fibre rules are exact for the second moments of the supported geometric shapes (3 × 3
/// Simpson points per rectangular cell; sectors with a midpoint rule in θ, which integrates
/// cos²θ exactly for N ≥ 3, and Simpson in r), so the elastic fibre stiffness equals the closed
/// form to round-off; the Simpson points include the section's surface, so a plastic section
/// (elements/beam.h) yields first exactly where the closed form says.
#include <Eigen/Core>

#include <functional>
#include <string>
#include <vector>

#include "core/model.h"

namespace impactfe {

/// One section integration point: position in the section axes (y, z) from the centroid, area.
struct BeamFibre {
  double y = 0.0;
  double z = 0.0;
  double area = 0.0;
};

/// Properties of a beam section (section axes y, z; beam axis x). Iyy = ∫z² dA (bending about
/// y), Izz = ∫y² dA, Iyz = ∫yz dA, J torsion constant. Shear areas: kA for shear along y and z;
/// 0 means shear-rigid (Euler–Bernoulli) in that direction.
struct BeamSectionProperties {
  std::string subtype;  // RECT, CSOLID, CTUBE, I, HREC, ASEC
  double area = 0.0;
  double iyy = 0.0;
  double izz = 0.0;
  double iyz = 0.0;
  double torsion = 0.0;  // J
  double warping = 0.0;  // Iw (ASEC only; stored, not used without the warping DOF)
  double shear_area_y = 0.0;
  double shear_area_z = 0.0;
  /// Centroid in the input coordinates of the section (where the SECDATA shape is drawn).
  double centroid_y = 0.0;
  double centroid_z = 0.0;
  /// Extreme fibres from the centroid, for the bending stresses (SBYT at y_max, ...).
  double y_min = 0.0, y_max = 0.0, z_min = 0.0, z_max = 0.0;
  std::vector<BeamFibre> fibres;
  /// How the shear areas were obtained (for the log): "5/6 A", "Cowper (ν = 0.3)", ...
  std::string shear_note;
  /// Added mass per length (SECCONTROL ADDMAS).
  double added_mass = 0.0;
};

/// Properties of a SECTYPE,,BEAM section from its subtype and SECDATA values, with Poisson's
/// ratio `nu` for the shear correction that depends on it (CTUBE, Cowper 1966). Throws
/// std::invalid_argument with a user message (e.g. "RECT: B must be positive") for bad data.
BeamSectionProperties beam_section_properties(const std::string& subtype,
                                              const std::vector<double>& data, double nu = 0.3);

/// The beam section subtypes impactfe computes, the default (RECT) first.
const std::vector<std::string>& beam_section_subtypes();

/// One line for the log: "A = 6, Iyy = 4.5, Iyz = 0, Izz = 2, J = 4.06, ...".
std::string describe_beam_section(const BeamSectionProperties& p);

/// Stress and tangent modulus of fibre `fibre` at axial strain `strain` (the material law).
using FibreLaw = std::function<void(int fibre, double strain, double& stress, double& tangent)>;

/// Generalised section strains e = (ε0, κy, κz) → resultants s = (N, My, Mz) and the section
/// tangent D = ∂s/∂e, integrated over the fibres with the fibre strain ε = ε0 + z κy − y κz.
void integrate_fibres(const std::vector<BeamFibre>& fibres, const Eigen::Vector3d& e,
                      const FibreLaw& law, Eigen::Vector3d& s, Eigen::Matrix3d& D);

}  // namespace impactfe
