#pragma once
/// What the beam element types share when they are built from an element record (BEAM188,
/// BEAM189, BEAM4, BEAM3): the element axes of APDL_MODELING §8.1, the SECTYPE,,BEAM section of
/// the record, and the nominal extreme-fibre stresses of the section resultants.
#include <Eigen/Core>

#include <string>
#include <vector>

#include "core/errors.h"
#include "core/model.h"
#include "elements/beam_section.h"
#include "elements/element_registry.h"

namespace impactfe {

/// "element 7 (BEAM189): <msg>" at the record's E command.
InputError beam_element_error(const ElementRecord& record, const char* name,
                              const std::string& msg);

/// Element axes (columns x, y, z) of a beam from I to J. With an orientation node at `xk`:
/// I, J, K span the x-z plane, z toward K. Without: y parallel to the global X-Y plane
/// (y = Z × x normalised), or y = global Y when the element is parallel to Z; then a rotation
/// THETA (degrees) about x (APDL_MODELING §8.1, §8.2).
Eigen::Matrix3d beam_frame(const ElementRecord& record, const char* name, const Vec3& xi,
                           const Vec3& xj, const Vec3* xk, double theta_deg);

/// The properties of the SECTYPE,,BEAM section the record's SECNUM names (InputError when it
/// names none or its data is bad); `nu` is Poisson's ratio of the shear correction. The
/// section's SECCONTROL shear stiffnesses become shear areas of `shear_modulus`, its ADDMAS the
/// added mass per length.
BeamSectionProperties record_beam_section(const Model& model, const ElementRecord& record,
                                          const char* name, double nu, double shear_modulus);

/// Nominal (elastic) stresses of the resultants N, My, Mz of a section with elastic section
/// stiffness D (elements/beam_section.h): σ = E (ε0 + z κy − y κz) at the extreme fibres, with
/// (ε0, κy, κz) = D⁻¹ (N, My, Mz).
struct BeamFibreStresses {
  double sdir = 0.0;              // axial
  double sbyt = 0.0, sbyb = 0.0;  // bending at y_max, y_min
  double sbzt = 0.0, sbzb = 0.0;  // bending at z_max, z_min
  double smax = 0.0, smin = 0.0;  // SDIR + the larger/smaller bending parts
};
BeamFibreStresses beam_fibre_stresses(const BeamSectionProperties& p, double youngs_modulus,
                                      const Eigen::Matrix3d& D, double N, double My, double Mz);

/// Result sequences `item` first, first + 1, ... named `names` (an empty name skips its number):
/// the SMISC / NMISC tables of the beam types.
std::vector<ResultSequence> numbered_sequences(const char* item, int first,
                                               const std::vector<std::string>& names);

}  // namespace impactfe
