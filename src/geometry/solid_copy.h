#pragma once
/// Copies and moves of solid-model entities (KGEN, LGEN, AGEN, VGEN; APDL_MODELING §3.1, §3.5),
/// and their reflections (KSYMM, LSYMM, ARSYM, VSYMM):
/// each copy is displaced by the increments DX, DY, DZ of a coordinate system (DR, Dθ, DZ in a
/// cylindrical one) relative to the previous copy. Copies take their lower entities along
/// (an area its lines and keypoints), keep the pattern's attributes and, unless NOELEM = 1,
/// the pattern's mesh. A rigid step (a translation, or a rotation about the system axis) moves
/// arcs as arcs; otherwise lines keep their path system between the new keypoints.
#include <vector>

#include "core/errors.h"
#include "core/model.h"
#include "geometry/mesher.h"

namespace impactfe::geometry {

enum class SolidKind { Keypoint, Line, Area, Volume };

struct CopyRequest {
  SolidKind kind = SolidKind::Keypoint;
  std::vector<int> pattern;  // entity numbers
  int copies = 1;            // ITIME − 1
  CoordinateSystem system;   // the active system of the command
  Vec3 increment = Vec3::Zero();
  int kinc = 0;           // keypoint number increment between copies (0: lowest free)
  bool copy_mesh = true;  // NOELEM = 0
  bool move = false;      // IMOVE = 1: move the pattern instead of copying it
  /// KSYMM / LSYMM / ARSYM / VSYMM: the component (0 X, 1 Y, 2 Z) of the active Cartesian system
  /// that the one copy reflects, about the plane through its origin; -1 for a displacement.
  int mirror = -1;
};

/// Runs a copy or move; mesh copies are created through `mesher` (its created_elements()).
void copy_solid(Model& model, const CopyRequest& request, Mesher& mesher,
                const SourceLocation& where);

}  // namespace impactfe::geometry
