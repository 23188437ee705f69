// CAD files through Gmsh's OpenCASCADE importer (IGESIN): the file's points, curves, surfaces and
// volumes become keypoints, lines, areas and volumes of the solid model, which the mappers and
// the free mesher then mesh like any other. What the solid model can hold is carried over
// exactly: straight lines, circular arcs, planar areas (holes allowed), and 3- or 4-sided
// cylindrical or conical areas (the ruled Coons patch of their boundary is the surface itself).
// Other curves and surfaces (B-splines, closed curves without a vertex) are refused by name.
#include "geometry/cad_import.h"

#include <fcntl.h>
#include <unistd.h>
#include <Eigen/Eigenvalues>
#include <Eigen/Geometry>

#include <algorithm>
#include <cctype>
#include <cmath>
#include <cstdio>
#include <fstream>
#include <map>
#include <set>

#include "geometry/gmsh_session.h"
#include "geometry/line_geometry.h"
#include "geometry/solid_builder.h"

namespace impactfe::geometry {

namespace {

std::string lower(std::string s) {
  for (char& c : s) c = static_cast<char>(std::tolower(static_cast<unsigned char>(c)));
  return s;
}

/// Millimetres per length unit of an IGES file (global section parameter 14, the unit flag;
/// IGES 5.3 §2.2.4.3.14): OpenCASCADE converts coordinates to millimetres, and this factor takes
/// them back to the file's own unit. 1 when the flag cannot be read.
double iges_unit_mm(const std::string& path) {
  std::ifstream in(path);
  std::string line, global;
  while (std::getline(in, line))
    if (line.size() >= 73 && line[72] == 'G') global += line.substr(0, 72);
  if (global.size() < 4) return 1.0;
  // Parameter and record delimiters: "1H," and "1H;" unless given otherwise (parameters 1, 2).
  char pd = ',';
  if (global.compare(0, 2, "1H") == 0) pd = global[2];
  std::vector<std::string> fields;
  std::string cur;
  for (std::size_t i = 0; i < global.size(); ++i) {
    const char c = global[i];
    // Hollerith strings nH...: skip n characters.
    if (cur.find_first_not_of("0123456789 ") == std::string::npos && (c == 'H' || c == 'h') &&
        !cur.empty() && cur.find_first_not_of(' ') != std::string::npos) {
      const std::size_t n = static_cast<std::size_t>(std::stoul(cur));
      cur.assign(1, 'H');
      cur.append(global, i + 1, n);
      i += n;
      continue;
    }
    if (c == pd || c == ';') {
      fields.push_back(cur);
      cur.clear();
      if (c == ';') break;
    } else {
      cur += c;
    }
  }
  if (fields.size() < 14) return 1.0;
  std::string flag = fields[13];
  flag.erase(std::remove(flag.begin(), flag.end(), ' '), flag.end());
  // 1 inch, 2 mm, 4 ft, 5 mile, 6 m, 7 km, 8 mil, 9 micron, 10 cm, 11 microinch.
  static const std::map<std::string, double> units = {
      {"1", 25.4},  {"2", 1.0},    {"4", 304.8},  {"5", 1609344.0}, {"6", 1000.0},
      {"7", 1.0e6}, {"8", 0.0254}, {"9", 1.0e-3}, {"10", 10.0},     {"11", 2.54e-5}};
  const auto it = units.find(flag);
  return it == units.end() ? 1.0 : it->second;
}

/// Imports the CAD file into the current Gmsh model: IGES in its own unit, STEP in millimetres
/// (OpenCASCADE's conversion).
void import_shapes(const std::string& path) {
  gmsh::vectorpair out;
  {
    // OpenCASCADE's IGES reader prints its entity count on the standard output whatever Gmsh's
    // verbosity: the run's output (a deck's *VWRITE, PRNSOL) is kept clean of it.
    std::fflush(stdout);
    const int saved = dup(1);
    const int null = open("/dev/null", O_WRONLY);
    if (saved >= 0 && null >= 0) dup2(null, 1);
    struct Restore {
      int saved, null;
      ~Restore() {
        std::fflush(stdout);
        if (saved >= 0) dup2(saved, 1), close(saved);
        if (null >= 0) close(null);
      }
    } restore{saved, null};
    gmsh::model::occ::importShapes(path, out, false);
  }
  const std::string ext = lower(path.substr(path.find_last_of('.') + 1));
  if (ext == "igs" || ext == "iges") {
    const double mm = iges_unit_mm(path);
    if (mm != 1.0) {
      gmsh::vectorpair all;
      gmsh::model::occ::getEntities(all, -1);
      gmsh::model::occ::dilate(all, 0.0, 0.0, 0.0, 1.0 / mm, 1.0 / mm, 1.0 / mm);
    }
  }
  gmsh::model::occ::synchronize();
}

Vec3 point_of(int tag) {
  std::vector<double> x;
  gmsh::model::getValue(0, tag, {}, x);
  return Vec3(x[0], x[1], x[2]);
}

/// A CAD entity the solid model cannot hold.
[[noreturn]] void refuse_cad(const SourceLocation& where, const std::string& path,
                             const std::string& what) {
  throw InputError(where, fmt::format("{}: {}", path, what));
}

/// The path of line `l` (from xa to xb) fitted to the samples `p` of a curve (ends a, b, middle
/// m): straight when every sample lies on the chord, else the circle through the ends and the
/// middle when every sample lies on it. False when it is neither.
bool fit_line_path(Line& l, const std::vector<Vec3>& p, double tol, const Vec3& xa,
                   const Vec3& xb) {
  constexpr int kSamples = 16;
  const Vec3 a = p.front(), m = p[kSamples / 2], b = p.back();
  const Vec3 chord = (b - a).normalized();
  double off_chord = 0.0;
  for (const Vec3& q : p)
    off_chord = std::max(off_chord, ((q - a) - (q - a).dot(chord) * chord).norm());
  if (off_chord <= tol) {
    set_line_path(l, xa, xb, CoordinateSystem{});
    return true;
  }
  // The circle through the ends and the middle: centre, axis by the right-hand rule from
  // the start through the middle, the sweep as the two half angles.
  const Vec3 u = m - a, v = b - a, w = u.cross(v);
  if (w.norm() > 1e-12 * u.norm() * v.norm()) {
    const Vec3 c =
        a + (v.squaredNorm() * w.cross(u) + u.squaredNorm() * v.cross(w)) / (2.0 * w.squaredNorm());
    const Vec3 axis = w.normalized();
    const double r = (a - c).norm();
    bool on_circle = true;
    for (const Vec3& q : p)
      on_circle =
          on_circle && std::abs((q - c).norm() - r) <= tol && std::abs((q - c).dot(axis)) <= tol;
    if (on_circle) {
      auto angle = [&](const Vec3& e, const Vec3& f) {
        return std::atan2((e - c).cross(f - c).dot(axis), (e - c).dot(f - c)) * 180.0 / M_PI;
      };
      set_arc_path(l, xa, c, axis, angle(a, m) + angle(m, b));
      return true;
    }
  }
  return false;
}

/// CAD curve `tag` as a line of `made` between the keypoints of its end points.
Line cad_line(int tag, const SolidModel& made, const std::map<int, int>& kp_of,
              const std::string& path, const SourceLocation& where) {
  std::vector<int> up, down;
  gmsh::model::getAdjacencies(1, tag, up, down);
  std::string type;
  gmsh::model::getType(1, tag, type);
  if (down.size() != 2 || down[0] == down[1])
    refuse_cad(where, path,
               fmt::format("curve {} ({}) is closed: a line needs two end keypoints (split "
                           "closed curves in the CAD program)",
                           tag, type));
  // The curve by samples (its OpenCASCADE type may be a trimmed or B-spline form of a
  // line or circle): straight, a circular arc, or refused.
  std::vector<double> lo, hi;
  gmsh::model::getParametrizationBounds(1, tag, lo, hi);
  constexpr int kSamples = 16;
  std::vector<double> params, x;
  for (int k = 0; k <= kSamples; ++k) params.push_back(lo[0] + (hi[0] - lo[0]) * k / kSamples);
  gmsh::model::getValue(1, tag, params, x);
  std::vector<Vec3> p;
  for (int k = 0; k <= kSamples; ++k) p.emplace_back(x[3 * k], x[3 * k + 1], x[3 * k + 2]);
  const Vec3 a = p.front();
  double length = 0.0;
  for (int k = 0; k < kSamples; ++k) length += (p[k + 1] - p[k]).norm();
  const double tol = 1e-7 * std::max(length, 1e-30);
  // Ends in the curve's own direction (the parametrisation's), then the keypoints there.
  const int ka = (made.keypoints.at(kp_of.at(down[0])).x - a).norm() <=
                         (made.keypoints.at(kp_of.at(down[1])).x - a).norm()
                     ? kp_of.at(down[0])
                     : kp_of.at(down[1]);
  const int kb = ka == kp_of.at(down[0]) ? kp_of.at(down[1]) : kp_of.at(down[0]);
  Line l;
  l.id = lowest_free(made.lines, made.numstr.line);
  l.kp1 = ka;
  l.kp2 = kb;
  const Vec3 xa = made.keypoints.at(ka).x, xb = made.keypoints.at(kb).x;
  if (!fit_line_path(l, p, tol, xa, xb))
    refuse_cad(where, path,
               fmt::format("curve {} (OpenCASCADE {}) is neither straight nor a circular arc: "
                           "the solid model holds straight lines and circular arcs",
                           tag, type));
  return l;
}

/// CAD surface `tag` as an area of `made` on the lines of its boundary curves: planar (by
/// samples of the surface and of its boundary), or a 3- or 4-sided cylinder or cone, whose
/// ruled Coons patch is the surface itself.
Area cad_area(int tag, const SolidModel& made, const std::map<int, int>& line_of,
              const std::string& path, const SourceLocation& where) {
  std::string type;
  gmsh::model::getType(2, tag, type);
  gmsh::vectorpair bnd;
  gmsh::model::getBoundary({{2, tag}}, bnd, false, true, false);
  Area a;
  a.id = lowest_free(made.areas, made.numstr.area);
  for (const auto& [d, t] : bnd) {
    const int l = line_of.at(std::abs(t));
    a.lines.push_back(t < 0 ? -l : l);
    const Line& line = made.lines.at(l);
    a.keypoints.push_back(t < 0 ? line.kp2 : line.kp1);
  }
  std::vector<double> lo, hi, x;
  gmsh::model::getParametrizationBounds(2, tag, lo, hi);
  std::vector<double> uv;
  for (int i = 0; i <= 4; ++i)
    for (int j = 0; j <= 4; ++j)
      uv.insert(uv.end(), {lo[0] + (hi[0] - lo[0]) * i / 4, lo[1] + (hi[1] - lo[1]) * j / 4});
  gmsh::model::getValue(2, tag, uv, x);
  std::vector<Vec3> p;
  for (std::size_t k = 0; k + 2 < x.size(); k += 3) p.emplace_back(x[k], x[k + 1], x[k + 2]);
  for (int sl : a.lines)
    for (int k = 0; k <= 8; ++k) p.push_back(line_point(made.lines.at(std::abs(sl)), k / 8.0));
  Eigen::AlignedBox3d box;
  Vec3 mean = Vec3::Zero();
  for (const Vec3& q : p) box.extend(q), mean += q / static_cast<double>(p.size());
  Eigen::Matrix3d scatter = Eigen::Matrix3d::Zero();
  for (const Vec3& q : p) scatter += (q - mean) * (q - mean).transpose();
  const Eigen::SelfAdjointEigenSolver<Eigen::Matrix3d> eig(scatter);
  const Vec3 normal = eig.eigenvectors().col(0);
  double off_plane = 0.0;
  for (const Vec3& q : p) off_plane = std::max(off_plane, std::abs((q - mean).dot(normal)));
  const bool planar = off_plane <= 1e-7 * std::max(box.diagonal().norm(), 1e-30);
  const bool ruled =
      (type == "Cylinder" || type == "Cone") && a.lines.size() >= 3 && a.lines.size() <= 4;
  if (!planar && !ruled)
    refuse_cad(where, path,
               fmt::format("surface {} (OpenCASCADE {}, {} sides) is not planar: the solid "
                           "model holds planar areas and 3- or 4-sided cylindrical or conical "
                           "ones",
                           tag, type, a.lines.size()));
  return a;
}

/// The entities of the current Gmsh model into `made`: points as keypoints, curves as lines,
/// surfaces as areas, volumes as volumes.
void cad_entities(SolidModel& made, CadImportCounts& counts, const std::string& path,
                  const SourceLocation& where) {
  gmsh::vectorpair ents;
  gmsh::model::getEntities(ents, 0);
  std::map<int, int> kp_of;  // CAD point -> keypoint
  for (const auto& [dim, tag] : ents) {
    const int id = lowest_free(made.keypoints, made.numstr.kp);
    Keypoint k;
    k.id = id;
    k.x = point_of(tag);
    made.keypoints[id] = k;
    kp_of[tag] = id;
    ++counts.keypoints;
  }
  gmsh::model::getEntities(ents, 1);
  std::map<int, int> line_of;
  for (const auto& [dim, tag] : ents) {
    const Line l = cad_line(tag, made, kp_of, path, where);
    made.lines[l.id] = l;
    line_of[tag] = l.id;
    ++counts.lines;
  }
  gmsh::model::getEntities(ents, 2);
  std::map<int, int> area_of;
  for (const auto& [dim, tag] : ents) {
    const Area a = cad_area(tag, made, line_of, path, where);
    made.areas[a.id] = a;
    area_of[tag] = a.id;
    ++counts.areas;
  }
  gmsh::model::getEntities(ents, 3);
  for (const auto& [dim, tag] : ents) {
    std::vector<int> up, down;
    gmsh::model::getAdjacencies(3, tag, up, down);
    const int id = lowest_free(made.volumes, made.numstr.volu);
    Volume v;
    v.id = id;
    for (int t : down) v.areas.push_back(area_of.at(t));
    made.volumes[id] = v;
    ++counts.volumes;
  }
}

}  // namespace

CadImportCounts import_cad(Model& model, const std::string& path, const SourceLocation& where) {
  SolidModel& s = model.solid;
  {
    std::ifstream probe(path);
    if (!probe) throw InputError(where, fmt::format("cannot open CAD file '{}'", path));
  }
  const std::string ext = lower(path.substr(path.find_last_of('.') + 1));
  if (ext != "igs" && ext != "iges" && ext != "stp" && ext != "step")
    throw InputError(where, fmt::format("'{}' is neither an IGES (.igs, .iges) nor a STEP (.stp, "
                                        ".step) file",
                                        path));
  CadImportCounts counts;
  GmshSession session("cad");
  // Built apart and added at the end: a refused entity leaves the model as it was.
  SolidModel made = s;
  with_gmsh(where, "read " + path, [&] {
    import_shapes(path);
    cad_entities(made, counts, path, where);
  });
  for (const auto& [id, k] : made.keypoints)
    if (s.keypoints.count(id) == 0) model.selection.keypoints.forget(id);
  for (const auto& [id, l] : made.lines)
    if (s.lines.count(id) == 0) model.selection.lines.forget(id);
  for (const auto& [id, a] : made.areas)
    if (s.areas.count(id) == 0) model.selection.areas.forget(id);
  for (const auto& [id, v] : made.volumes)
    if (s.volumes.count(id) == 0) model.selection.volumes.forget(id);
  s = std::move(made);
  return counts;
}

double cad_measure(const std::string& path, int dim) {
  double total = 0.0;
  GmshSession session("measure");
  with_gmsh(SourceLocation{}, "measure " + path, [&] {
    import_shapes(path);
    gmsh::vectorpair ents;
    gmsh::model::getEntities(ents, dim);
    for (const auto& [d, tag] : ents) {
      double m = 0.0;
      gmsh::model::occ::getMass(d, tag, m);
      total += m;
    }
  });
  return total;
}

}  // namespace impactfe::geometry
