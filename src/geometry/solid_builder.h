#pragma once
/// Creation of solid-model entities with MAPDL numbering (APDL_MODELING §3.0-§3.4): keypoints,
/// lines (straight in a system, arcs), areas bounded by a loop of lines, volumes bounded by
/// areas, and the working-plane primitives. New entities take the lowest free number not below
/// the NUMSTR start; lines and areas that already join the same keypoints are reused. Errors are
/// InputError at `where`.
#include <vector>

#include "core/errors.h"
#include "core/solid_model.h"

namespace impactfe::geometry {

/// Lowest number ≥ start (and ≥ 1) not used in `map`.
template <class Map>
int lowest_free(const Map& map, int start) {
  int id = start < 1 ? 1 : start;
  for (auto it = map.lower_bound(id); it != map.end() && it->first == id; ++it) ++id;
  return id;
}

class SolidBuilder {
 public:
  SolidBuilder(SolidModel& solid, const SourceLocation& where) : s_(solid), where_(where) {}

  /// K: defines (id > 0) or creates (id = 0: lowest free) a keypoint at global x. Redefining a
  /// keypoint used by a line is an error.
  int keypoint(int id, const Vec3& x);
  /// A line joining keypoints a → b, straight in `path` (new, number `id` or the lowest free).
  int line(int a, int b, const CoordinateSystem& path, int id = 0);
  /// A circular arc a → b about `centre` (axis `axis`, sweep in degrees, right-hand rule).
  int arc(int a, int b, const Vec3& centre, const Vec3& axis, double sweep_deg);
  /// A copy of line `line` between keypoints a and b moved by the rigid motion x → R x + t (the
  /// path system moves with it, so arcs stay arcs).
  int moved_line(int line, int a, int b, const Mat3& R, const Vec3& t);
  /// The line joining a and b: signed number (negative when it runs b → a), 0 when none.
  int find_line(int a, int b) const;
  /// The existing line a–b (signed) or a new one straight in `path`.
  int line_between(int a, int b, const CoordinateSystem& path);
  /// AL: an area bounded by `lines` (one closed loop, any order; the sign of the first one sets
  /// the direction, hence the normal).
  int area_from_lines(std::vector<int> lines);
  /// A: the area through keypoints in order (≥ 3), missing lines straight in `path`. An existing
  /// area over the same keypoints is reused.
  int area_from_keypoints(const std::vector<int>& kps, const CoordinateSystem& path);
  /// VA: a volume bounded by `areas` (≥ 4, a closed shell: every line on exactly two areas).
  int volume_from_areas(const std::vector<int>& areas);
  /// The order in which a volume through keypoints numbers its new areas.
  enum class FaceOrder {
    Primitive,   // BLOCK: bottom, top, then the sides I-J, J-K, K-L, L-I
    BrickFaces,  // V: the brick's faces 1-6: bottom, the sides I-J ... L-I, top last
  };
  /// V: a volume through 8 keypoints (bottom I..L, top M..P; repeated keypoints give a prism or
  /// a pyramid), missing lines straight in `path`; an area the volume shares with an existing
  /// one is reused, so the new areas take the numbers in `order` skipping it.
  int volume_from_keypoints(const std::vector<int>& kps, const CoordinateSystem& path,
                            FaceOrder order = FaceOrder::BrickFaces);

  /// RECTNG / BLC4 / BLC5 (depth 0): rectangle x1..x2, y1..y2 in the working plane `wp`.
  int rectangle(const CoordinateSystem& wp, double x1, double x2, double y1, double y2);
  /// BLOCK / BLC4 / BLC5 (depth ≠ 0): box in the working plane.
  int block(const CoordinateSystem& wp, double x1, double x2, double y1, double y2, double z1,
            double z2);
  /// CYL4 / CYLIND: circle, annulus or sector about (xc, yc) in the working plane from θ1 to θ2
  /// (degrees), as an area (z1 == z2) or a volume from z1 to z2. Full circles are made of four
  /// 90° arcs.
  int cylinder(const CoordinateSystem& wp, double xc, double yc, double r1, double r2,
               double theta1, double theta2, double z1, double z2);

  /// Corner keypoints of an area in loop order (from its lines).
  std::vector<int> area_keypoints(const std::vector<int>& signed_lines) const;
  /// Every line of the given areas (unique, ascending).
  std::vector<int> lines_of_areas(const std::vector<int>& areas) const;

 private:
  [[noreturn]] void fail(const std::string& message) const;
  const Keypoint& kp(int id) const;

  SolidModel& s_;
  SourceLocation where_;
};

}  // namespace impactfe::geometry
