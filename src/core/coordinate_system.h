#pragma once
/// Coordinate systems (APDL_MODELING §2): global Cartesian 0, cylindrical 1 (axis Z), spherical 2,
/// the working plane 4, the predefined cylindrical systems 5 (axis Y) and 6 (axis X), and the
/// user systems 11+ (LOCAL, CLOCAL). Coordinates are (x, y, z), (R, θ, Z) or (R, θ, φ) with the
/// angles in degrees; θ lies in (−180, 180], φ is the elevation from the system's x-y plane.
#include <Eigen/Core>

#include <map>

namespace impactfe {

using Vec3 = Eigen::Vector3d;
using Mat3 = Eigen::Matrix3d;

enum class CsysKind { Cartesian = 0, Cylindrical = 1, Spherical = 2 };

/// Rotation R = Rz(THXY)·Rx(THYZ)·Ry(THZX) of three angles in degrees: THXY about Z, then THYZ
/// about the new X, then THZX about the new Y (APDL_MODELING §2.1, M21). Columns of R are the
/// rotated axes in the parent's components.
Mat3 rotation_from_angles(const Vec3& angles_deg);
/// The angles (THXY, THYZ, THZX) in degrees of a rotation matrix, inverse of
/// rotation_from_angles (THYZ in [−90, 90]; at THYZ = ±90 the split of THXY and THZX is chosen
/// with THZX = 0).
Vec3 angles_from_rotation(const Mat3& r);

/// One coordinate system: kind, origin and axes (columns: local x, y, z in global components).
struct CoordinateSystem {
  CsysKind kind = CsysKind::Cartesian;
  Vec3 origin = Vec3::Zero();
  Mat3 axes = Mat3::Identity();

  /// Global Cartesian position of the point with coordinates `c` in this system.
  Vec3 to_global(const Vec3& c) const;
  /// Coordinates in this system of the global point `x` (θ in (−180, 180]).
  Vec3 from_global(const Vec3& x) const;
  /// Orthonormal axes of the system at the global point `x` (columns): the system axes for a
  /// Cartesian system; radial, tangential, axial for a cylindrical one; radial, θ and φ
  /// directions for a spherical one. Returns false when `x` lies on the axis (R ≈ 0, no radial
  /// direction); `out` is then the system axes.
  bool axes_at(const Vec3& x, Mat3& out) const;
  /// Angular coordinates are periodic (θ in the curvilinear systems, φ too in spherical ones).
  bool curvilinear() const { return kind != CsysKind::Cartesian; }
};

/// The working plane (APDL_MODELING §2.5): origin and axes; primitives are built in it and
/// CSYS,4 refers to it.
struct WorkingPlane {
  Vec3 origin = Vec3::Zero();
  Mat3 axes = Mat3::Identity();
  bool polar = false;  // WPCSYS on a curvilinear system: CSYS,4 is then cylindrical
  CoordinateSystem as_system() const;
};

/// All coordinate systems of a model and the active one (CSYS).
class CoordinateSystems {
 public:
  /// The predefined systems 0, 1, 2, 5 and 6; the working plane is the global X-Y plane.
  CoordinateSystems();

  bool has(int id) const { return id == 4 || systems_.count(id) != 0; }
  /// System `id` (4: the working plane). Precondition: has(id).
  CoordinateSystem get(int id) const;
  /// Defines or redefines a user system (id > 10).
  void define(int id, const CoordinateSystem& system) { systems_[id] = system; }
  /// Deletes a user system; predefined ones (< 11) stay. Returns false when it did not exist.
  bool remove(int id);
  /// The active system (CSYS).
  CoordinateSystem active_system() const { return get(active); }
  const std::map<int, CoordinateSystem>& systems() const { return systems_; }

  int active = 0;
  WorkingPlane working_plane;

 private:
  std::map<int, CoordinateSystem> systems_;
};

}  // namespace impactfe
