#pragma once
/// Geometry of solid-model lines (APDL_MODELING §3.2): a line is "straight in its path system",
/// i.e. the linear interpolation of its end coordinates in that system.
#include "core/solid_model.h"

namespace impactfe::geometry {

/// Sets the path of `line` to `path` with end points a and b (global): straight in a Cartesian
/// path, the shorter way round (|Δθ| ≤ 180°) in a curvilinear one. An end on the axis (R ≈ 0)
/// takes the other end's angles.
void set_line_path(Line& line, const Vec3& a, const Vec3& b, const CoordinateSystem& path);
/// Sets a circular arc about `centre` with unit axis `axis` from a (global) sweeping
/// `sweep_deg` degrees (right-hand rule about the axis) to the line's second keypoint.
void set_arc_path(Line& line, const Vec3& a, const Vec3& centre, const Vec3& axis,
                  double sweep_deg);
/// Point of the line at parameter s in [0, 1] (global Cartesian).
Vec3 line_point(const Line& line, double s);
/// Parameter s in [0, 1] of the point of the line closest to x (sampled, then refined by golden
/// section: for the nodes a line's mesh placed on it).
double line_parameter(const Line& line, const Vec3& x);
/// Length (Gauss quadrature of the speed in the path coordinates; exact for straight lines).
double line_length(const Line& line);
/// Angle (degrees) swept about the path axis: 0 for lines of a Cartesian path.
double line_sweep_angle(const Line& line);
/// Centroid of the line (LSEL,LOC): the mean of its points.
Vec3 line_centroid(const Line& line);
/// Centroid of an area (ASEL,LOC): area-weighted over a Coons sampling of 3- and 4-sided areas,
/// the mean of the boundary otherwise.
Vec3 area_centroid(const SolidModel& solid, const Area& area);
/// Centroid of a volume (VSEL,LOC): the mean of its areas' centroids.
Vec3 volume_centroid(const SolidModel& solid, const Volume& volume);
/// The point at fraction s of the way from a to b "straight in `system`" (FILL, KFILL and the
/// generation commands interpolate in the active coordinate system).
Vec3 interpolate_in_system(const CoordinateSystem& system, const Vec3& a, const Vec3& b, double s);

}  // namespace impactfe::geometry
