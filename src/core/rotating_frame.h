#pragma once
/// The rotational inertia loads of MAPDL (OMEGA, DOMEGA, CGLOC, CGOMGA, DCGOMG) and the
/// acceleration field they give (Mechanical APDL Theory Reference, "Acceleration Effect"): the
/// structure turns with ω about the global origin, and the global system turns with Ω about the
/// point CGLOC (the origin of the acceleration system, axes parallel to the global ones).
#include "core/coordinate_system.h"
#include "core/errors.h"

namespace impactfe {

/// The rotational inertia loads of a load step (all in global Cartesian components).
struct RotationalLoads {
  Vec3 omega = Vec3::Zero();        // OMEGA: angular velocity of the structure (global origin)
  Vec3 domega = Vec3::Zero();       // DOMEGA: angular acceleration of the structure
  Vec3 cg_location = Vec3::Zero();  // CGLOC: origin of the acceleration system
  Vec3 cg_omega = Vec3::Zero();     // CGOMGA: angular velocity of the global system about CGLOC
  Vec3 cg_domega = Vec3::Zero();    // DCGOMG: angular acceleration of the global system
  SourceLocation where;             // the last of these commands that gave a non-zero value
  /// True when the loads accelerate the structure (CGLOC alone does not).
  bool any() const {
    return omega != Vec3::Zero() || domega != Vec3::Zero() || cg_omega != Vec3::Zero() ||
           cg_domega != Vec3::Zero();
  }
  bool operator==(const RotationalLoads& o) const {
    return omega == o.omega && domega == o.domega && cg_location == o.cg_location &&
           cg_omega == o.cg_omega && cg_domega == o.cg_domega;
  }
};

/// An acceleration field linear in the position x: a(x) = at_origin + gradient·x, with the
/// angular acceleration of the material (the acceleration of its rotations).
struct LinearAccelerationField {
  Vec3 at_origin = Vec3::Zero();
  Mat3 gradient = Mat3::Zero();
  Vec3 angular = Vec3::Zero();
  Vec3 at(const Vec3& x) const { return at_origin + gradient * x; }
  bool zero() const {
    return at_origin == Vec3::Zero() && gradient == Mat3::Zero() && angular == Vec3::Zero();
  }
};

/// The absolute acceleration of the material point at x that the rotational loads give:
///   a(x) = Ω̇×(x−c) + Ω×(Ω×(x−c)) + 2Ω×(ω×x) + ω̇×x + ω×(ω×x)
/// (c = CGLOC; the acceleration of a point moving with ω relative to a frame that turns with Ω
/// about c: transport, Coriolis and relative terms), and the angular acceleration of the
/// material, ω̇ + Ω̇ + Ω×ω (the derivative of Ω + ω in the fixed frame).
LinearAccelerationField rotational_acceleration(const RotationalLoads& loads);

}  // namespace impactfe
