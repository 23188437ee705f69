#pragma once
/// Layered shell sections (SECTYPE,,SHELL with one SECDATA per layer, APDL_MODELING §7.2):
/// each layer's plane-stress stiffness in the element axes (the layer's material axes turned by
/// θ about the shell normal), the laminate's A, B, D matrices of classical lamination theory
/// (Jones, Mechanics of Composite Materials, §4.2) and its transverse shear stiffness with the
/// shear correction factors of the equivalent-energy method, which MAPDL's layered shells use
/// (MAPDL theory reference, SHELL209/SHELL281 "Shear Correction"; Vlachoutsis 1992).
#include <Eigen/Core>

#include <string>
#include <vector>

#include "core/model.h"

namespace impactfe::shell {

/// Elastic constants of a shell layer's material in its own axes (1 along the material x axis,
/// 2 across it, 3 the shell normal): the orthotropic plane-stress set.
struct LayerElasticity {
  double E1 = 0.0, E2 = 0.0;
  double nu12 = 0.0;  // major Poisson's ratio: ε2 = −ν12 σ1 / E1
  double G12 = 0.0, G13 = 0.0, G23 = 0.0;
  double rho = 0.0;
  bool isotropic = true;  // E1 = E2 and G12 = G13 = G23 = E1 / (2 (1 + ν12))
};

/// The constants of material `m` (MP EX, EY, PRXY or NUXY, GXY, GXZ, GYZ, DENS) with MAPDL's
/// defaults: EY = EX; PRXY the major ratio, NUXY the minor one (PRXY = NUXY·EX/EY); GXY =
/// EX / (2 (1 + PRXY)); GXZ and GYZ = GXY. Throws std::invalid_argument with the reason.
LayerElasticity layer_elasticity(const Material& m, int id);

/// One layer in the element axes, z measured from the mid-surface of the section.
struct Ply {
  double z_bot = 0.0, z_top = 0.0;
  double theta_deg = 0.0;
  int material = 0;
  int points = 3;  // NUMPT: integration points through the layer (results only)
  /// (σx, σy, τxy) = Q (εx, εy, γxy), element axes.
  Eigen::Matrix3d Q = Eigen::Matrix3d::Zero();
  /// (τxz, τyz) = G (γxz, γyz), element axes, without the shear correction.
  Eigen::Matrix2d G = Eigen::Matrix2d::Zero();
  double rho = 0.0;
};

struct Laminate {
  std::vector<Ply> plies;  // bottom first
  double thickness = 0.0;
  /// N = A ε0 + B κ, M = B ε0 + D κ (N, M per unit length; ε0 mid-surface strain, κ curvature).
  Eigen::Matrix3d A = Eigen::Matrix3d::Zero(), B = Eigen::Matrix3d::Zero(),
                  D = Eigen::Matrix3d::Zero();
  /// Shear correction factors (k_xz, k_yz): the transverse shear stiffness is
  /// diag(k)^½ ∫G dz diag(k)^½. 5/6 for a homogeneous section.
  Eigen::Vector2d shear_factor = Eigen::Vector2d::Constant(5.0 / 6.0);
  /// (Qxz, Qyz) = shear (γxz, γyz): the transverse shear stiffness with the correction.
  Eigen::Matrix2d shear = Eigen::Matrix2d::Zero();
  double mass_per_area = 0.0;
  /// All layers of one material at one angle (the homogeneous section of a single SECDATA).
  bool homogeneous = true;
};

/// Layer input: thickness, elastic constants in the layer's axes, θ in degrees from the element
/// x axis, the material number and NUMPT.
struct LayerInput {
  double thickness = 0.0;
  LayerElasticity elasticity;
  double theta_deg = 0.0;
  int material = 0;
  int points = 3;
};

/// The laminate of the layers, bottom first; `homogeneous_factor` is the shear correction of a
/// homogeneous section (5/6). Throws std::invalid_argument for a non-positive thickness.
Laminate make_laminate(const std::vector<LayerInput>& layers,
                       double homogeneous_factor = 5.0 / 6.0);

/// The layers of shell section `section` (SECDATA Thickness, MAT (blank: `element_material`),
/// THETA, NUMPT). Throws std::invalid_argument with the reason.
std::vector<LayerInput> section_layers(const Model& model, const Section& section,
                                       int element_material);

/// The result names of a layered shell: `homogeneous` followed by SX SY SXY SEQV at the TOP, MID
/// and BOT of each of `layers` layers ("SX_L1_TOP", ...).
std::vector<std::string> with_layer_result_names(const std::vector<std::string>& homogeneous,
                                                 int layers);

/// The plane-stress stiffness of `e` in its own axes, turned by θ (degrees) into the element
/// axes: Q̄ = Tᵀ Q T with T the engineering-strain rotation (Jones eq. 2.84).
Eigen::Matrix3d rotated_plane_stiffness(const LayerElasticity& e, double theta_deg);
/// The transverse shear stiffness diag(G13, G23) turned by θ into the element axes.
Eigen::Matrix2d rotated_shear_stiffness(const LayerElasticity& e, double theta_deg);

}  // namespace impactfe::shell
