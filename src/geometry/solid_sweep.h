#pragma once
/// Volumes swept from areas (APDL_MODELING §4.5): VEXT (extrusion along a vector) and VROTAT
/// (revolution about an axis in segments of at most 90°). Each pattern area gives one volume
/// per segment bounded by the area, its moved copy and one side area per boundary line; areas
/// sharing a line share the side area, so the volumes are conforming. If the pattern areas are
/// meshed, the volumes are meshed by sweeping (EXTOPT: layers, attributes, ACLEAR).
#include <vector>

#include "core/errors.h"
#include "core/solid_model.h"
#include "geometry/mesher.h"

namespace impactfe::geometry {

struct SweptVolume {
  int volume = 0;
  int source = 0;   // the area it was swept from (the pattern area or the previous segment's top)
  int target = 0;   // its moved copy
  int pattern = 0;  // the original pattern area
  std::vector<int> connectors;  // lines along the sweep direction
};

/// VEXT: extrudes `areas` by the global vector d.
std::vector<SweptVolume> extrude_areas(SolidModel& solid, const std::vector<int>& areas,
                                       const Vec3& d, const SourceLocation& where);
/// VROTAT: revolves `areas` about the axis p1 → p2 by `arc` degrees (right-hand rule) in `nseg`
/// segments; a full 360° revolution closes onto the pattern areas. Keypoints on the axis are an
/// error (degenerate volumes).
std::vector<SweptVolume> revolve_areas(SolidModel& solid, const std::vector<int>& areas,
                                       const Vec3& p1, const Vec3& p2, double arc, int nseg,
                                       const SourceLocation& where);
/// Meshes the swept volumes of meshed pattern areas with the mesher's current pointers (or the
/// pattern attributes as EXTOPT asks), EXTOPT,ESIZE layers, and clears the pattern area
/// elements for EXTOPT,ON / EXTOPT,ACLEAR,1.
void mesh_swept_volumes(Mesher& mesher, SolidModel& solid, const std::vector<SweptVolume>& made);

}  // namespace impactfe::geometry
