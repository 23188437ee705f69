/// CONTA174 segment-to-segment integration points (elements/contact_segment.h): the target facets
/// of a real set as bilinear quadrilaterals and triangles, the integration cells from clipping the
/// contact face with each facet on the face's plane, and the Gauss points on a rigid target.
#include "elements/contact_segment.h"

#include <Eigen/Dense>
#include <algorithm>
#include <array>
#include <cmath>
#include <map>

#include "elements/element_build_cache.h"
#include "elements/line_element_data.h"
#include "elements/target_surface.h"

namespace impactfe {

/// The facets of a deformable target as TARGE170 gave them (3 or 4 nodes, not split), and the
/// facet of each of TargetSurface's triangles (found by their node triples).
struct SegmentFacets {
  struct Facet {
    std::vector<int> nodes;
    std::vector<Vec3> x;
    Vec3 normal;  // at the centre, right-hand rule of the node order
  };
  std::vector<Facet> facets;
  std::map<std::array<int, 3>, int> by_triangle;
};

namespace {

std::array<int, 3> sorted(int a, int b, int c) {
  std::array<int, 3> t = {a, b, c};
  std::sort(t.begin(), t.end());
  return t;
}

const SegmentFacets& segment_facets(const ElementBuildContext& ctx, int real) {
  std::shared_ptr<const SegmentFacets>& shared = build_cache(ctx).segment_facets[real];
  if (shared) return *shared;
  auto out = std::make_shared<SegmentFacets>();
  for (const auto& [id, rec] : ctx.model.elements) {
    const auto type = ctx.model.element_types.find(rec.type);
    if (rec.real != real || type == ctx.model.element_types.end() ||
        type->second.ansys_name != "TARGE170")
      continue;
    SegmentFacets::Facet f;
    for (int n : rec.nodes)
      if (std::find(f.nodes.begin(), f.nodes.end(), n) == f.nodes.end()) f.nodes.push_back(n);
    if (f.nodes.size() != 3 && f.nodes.size() != 4) continue;  // the pilot
    for (int n : f.nodes) f.x.push_back(ctx.model.nodes.at(n).x);
    const auto& x = f.x;
    f.normal =
        (f.nodes.size() == 3 ? (x[1] - x[0]).cross(x[2] - x[0]) : (x[2] - x[0]).cross(x[3] - x[1]))
            .normalized();
    const int index = static_cast<int>(out->facets.size());
    const auto& v = f.nodes;
    out->by_triangle.emplace(sorted(v[0], v[1], v[2]), index);
    if (v.size() == 4) out->by_triangle.emplace(sorted(v[0], v[2], v[3]), index);
    out->facets.push_back(std::move(f));
  }
  shared = std::move(out);
  return *shared;
}

/// The facets (indices into SegmentFacets) near y within `reach` that may touch the face: no
/// node in common with it and facing it (n_facet·n_face < 0).
std::vector<int> candidate_facets(const TargetSurface& surface, const SegmentFacets& facets,
                                  const Vec3& y, double reach, const std::vector<int>& face,
                                  const Vec3& normal) {
  std::vector<int> out;
  for (int t : surface.near(y, reach)) {
    const auto& nodes = surface.triangles()[static_cast<std::size_t>(t)].nodes;
    const auto it = facets.by_triangle.find(sorted(nodes[0], nodes[1], nodes[2]));
    if (it == facets.by_triangle.end()) continue;
    const SegmentFacets::Facet& f = facets.facets[static_cast<std::size_t>(it->second)];
    const bool shares = std::any_of(f.nodes.begin(), f.nodes.end(), [&](int n) {
      return std::find(face.begin(), face.end(), n) != face.end();
    });
    if (shares || !(f.normal.dot(normal) < 0.0)) continue;
    if (std::find(out.begin(), out.end(), it->second) == out.end()) out.push_back(it->second);
  }
  return out;
}

/// Every facet (indices into SegmentFacets) with a triangle near y within `reach`.
std::vector<int> all_facets_near(const TargetSurface& surface, const SegmentFacets& facets,
                                 const Vec3& y, double reach) {
  std::vector<int> out;
  for (int t : surface.near(y, reach)) {
    const auto& nodes = surface.triangles()[static_cast<std::size_t>(t)].nodes;
    const auto it = facets.by_triangle.find(sorted(nodes[0], nodes[1], nodes[2]));
    if (it != facets.by_triangle.end() &&
        std::find(out.begin(), out.end(), it->second) == out.end())
      out.push_back(it->second);
  }
  return out;
}

using Vec2 = Eigen::Vector2d;

double cross2(const Vec2& a, const Vec2& b) {
  return a(0) * b(1) - a(1) * b(0);
}

/// Sutherland–Hodgman: `subject` clipped by the convex counter-clockwise polygon `clip`.
std::vector<Vec2> clip_polygon(std::vector<Vec2> subject, const std::vector<Vec2>& clip) {
  for (std::size_t e = 0; e < clip.size() && !subject.empty(); ++e) {
    const Vec2 a = clip[e], b = clip[(e + 1) % clip.size()];
    const Vec2 edge = b - a;
    const double scale = edge.squaredNorm();
    const auto side = [&](const Vec2& p) { return cross2(edge, p - a) / scale; };
    std::vector<Vec2> out;
    for (std::size_t i = 0; i < subject.size(); ++i) {
      const Vec2 p = subject[i], q = subject[(i + 1) % subject.size()];
      const double sp = side(p), sq = side(q);
      if (sp >= 0.0) out.push_back(p);
      if ((sp >= 0.0) != (sq >= 0.0)) out.push_back(p + (sp / (sp - sq)) * (q - p));
    }
    subject = std::move(out);
  }
  return subject;
}

/// The contact face in its initial position: corners, centre, unit normal and a plane basis.
struct Face {
  std::vector<int> nodes;
  std::vector<Vec3> x;
  Vec3 centre, normal, e1, e2;
  std::vector<Vec2> plane;  // corners on the plane, counter-clockwise about the normal
  int k() const { return static_cast<int>(nodes.size()); }
  Vec2 to_plane(const Vec3& y) const { return {(y - centre).dot(e1), (y - centre).dot(e2)}; }
};

/// An integration point: the face's shape functions at it and its weight (area).
struct Station {
  std::vector<double> phi;
  double weight = 0.0;
  int facet = -1;  // the facet of its cell (-1: the face's own Gauss rule)
};

/// (ξ, η) of the plane point q on the face's projected corners (Newton on Σ N_i S_i = q).
Vec2 face_coordinates(const Face& face, const Vec2& q) {
  Vec2 xi = face.k() == 4 ? Vec2(0.0, 0.0) : Vec2(1.0 / 3.0, 1.0 / 3.0);
  for (int it = 0; it < 30; ++it) {
    const FacetShape s = facet_shape(face.k(), xi(0), xi(1));
    Vec2 r = q;
    Eigen::Matrix2d J = Eigen::Matrix2d::Zero();
    for (int i = 0; i < face.k(); ++i) {
      r -= s.N[i] * face.plane[static_cast<std::size_t>(i)];
      J.col(0) += s.dN[i][0] * face.plane[static_cast<std::size_t>(i)];
      J.col(1) += s.dN[i][1] * face.plane[static_cast<std::size_t>(i)];
    }
    const Vec2 d = J.inverse() * r;
    xi += d;
    if (d.norm() < 1e-14) break;
  }
  return xi;
}

/// The station at face coordinates ξ with `plane_weight` of plane area: the weight on the face
/// is the plane's times |a₁ × a₂| / |det J_plane| (the face's area element over its projection).
Station station(const Face& face, const Vec2& xi, double plane_weight, bool plane_measure) {
  const FacetShape s = facet_shape(face.k(), xi(0), xi(1));
  Vec3 a1 = Vec3::Zero(), a2 = Vec3::Zero();
  Eigen::Matrix2d J = Eigen::Matrix2d::Zero();
  Station st;
  for (int i = 0; i < face.k(); ++i) {
    st.phi.push_back(s.N[i]);
    a1 += s.dN[i][0] * face.x[static_cast<std::size_t>(i)];
    a2 += s.dN[i][1] * face.x[static_cast<std::size_t>(i)];
    J.col(0) += s.dN[i][0] * face.plane[static_cast<std::size_t>(i)];
    J.col(1) += s.dN[i][1] * face.plane[static_cast<std::size_t>(i)];
  }
  const double j3 = a1.cross(a2).norm();
  st.weight = plane_measure ? plane_weight * j3 / std::abs(J.determinant()) : plane_weight * j3;
  return st;
}

/// The face's own Gauss rule: 2 × 2 on a quadrilateral, 3 points (degree 2) on a triangle.
std::vector<Station> face_rule(const Face& face) {
  std::vector<Station> out;
  if (face.k() == 4) {
    const double g = 1.0 / std::sqrt(3.0);
    for (double eta : {-g, g})
      for (double xi : {-g, g}) out.push_back(station(face, Vec2(xi, eta), 1.0, false));
  } else {
    for (const Vec2& xi : {Vec2(1.0 / 6, 1.0 / 6), Vec2(2.0 / 3, 1.0 / 6), Vec2(1.0 / 6, 2.0 / 3)})
      out.push_back(station(face, xi, 1.0 / 6.0, false));
  }
  return out;
}

/// Dunavant's 6-point rule, degree 4 (Int. J. Numer. Meth. Eng. 21, 1985): area coordinates of
/// the first point of each orbit and its weight (the weights sum to 1).
constexpr double kDunavant[2][3] = {{0.445948490915965, 0.108103018168070, 0.223381589678011},
                                    {0.091576213509771, 0.816847572980459, 0.109951743655322}};

/// The cells of the face against each candidate facet: the clipped polygon, fanned into
/// triangles, 6 Dunavant points each.
std::vector<Station> cells(const Face& face, const SegmentFacets& facets,
                           const std::vector<int>& candidates, double area) {
  std::vector<Station> out;
  for (int f : candidates) {
    std::vector<Vec2> poly;
    for (const Vec3& y : facets.facets[static_cast<std::size_t>(f)].x)
      poly.push_back(face.to_plane(y));
    poly = clip_polygon(std::move(poly), face.plane);
    for (std::size_t j = 1; j + 1 < poly.size(); ++j) {
      const Vec2 &p0 = poly[0], &p1 = poly[j], &p2 = poly[j + 1];
      const double cell = 0.5 * std::abs(cross2(p1 - p0, p2 - p0));
      if (!(cell > 1e-12 * area)) continue;
      for (const auto& orbit : kDunavant)
        for (int r = 0; r < 3; ++r) {
          const double l[3] = {orbit[r == 0 ? 1 : 0], orbit[r == 1 ? 1 : 0], orbit[r == 2 ? 1 : 0]};
          const Vec2 q = l[0] * p0 + l[1] * p1 + l[2] * p2;
          Station st = station(face, face_coordinates(face, q), orbit[2] * cell, true);
          st.facet = f;
          out.push_back(std::move(st));
        }
    }
  }
  return out;
}

/// The contact face on `corners` (3 or 4 nodes) in its plane: centre, unit normal (the cross
/// product of the diagonals of a quadrilateral), in-plane axes e1 (along the first side) and e2,
/// and the corners in those axes; `area` the area the normal spans.
Face contact_face(const Model& model, const std::vector<int>& corners, double& area) {
  Face face;
  face.nodes = corners;
  for (int n : corners) face.x.push_back(model.nodes.at(n).x);
  const auto& x = face.x;
  face.centre = Vec3::Zero();
  for (const Vec3& y : x) face.centre += y / static_cast<double>(x.size());
  const Vec3 c =
      x.size() == 3 ? (x[1] - x[0]).cross(x[2] - x[0]) : (x[2] - x[0]).cross(x[3] - x[1]);
  area = 0.5 * c.norm();
  face.normal = c.normalized();
  face.e1 = ((x[1] - x[0]) - (x[1] - x[0]).dot(face.normal) * face.normal).normalized();
  face.e2 = face.normal.cross(face.e1);
  for (const Vec3& y : x) face.plane.push_back(face.to_plane(y));
  return face;
}

}  // namespace

std::vector<std::unique_ptr<ContactPoint>> segment_points(
    const ElementBuildContext& ctx, const ElementRecord& record, const std::vector<int>& corners,
    const std::vector<std::unique_ptr<ContactPoint>>& nodal, const char* family) {
  const Model& model = ctx.model;
  double area = 0.0;
  const Face face = contact_face(model, corners, area);
  const auto& x = face.x;

  // The face's stiffness per area: the nodal law's (tributary-area shares), k = Σ k_node / A.
  ContactLawData law = nodal.front()->law();
  double kn = 0.0, kt = 0.0;
  for (const auto& p : nodal) kn += p->law().kn, kt += p->law().kt;
  kn /= area;
  kt /= area;
  // PINB (real constant 6) and CNOF (10) as the nodal law reads them (target_point validated).
  const RealSet& real = line_data::real_set(model, record, family);
  double depth = 0.0;
  for (int n : corners) depth = std::max(depth, attached_depth(ctx, n));
  const double pinb = real.get(6) != 0.0 ? real.get(6) : 2.0;
  const double reach = pinb < 0.0 ? -pinb : pinb * depth;
  const double offset = real.get(10);

  std::shared_ptr<const TargetSurface> target = contact_target(ctx, record);
  std::vector<std::unique_ptr<ContactPoint>> points;
  const auto law_at = [&](const Station& st) {
    ContactLawData d = law;
    d.kn = kn * st.weight;
    d.kt = kt * st.weight;
    return d;
  };
  const auto position = [&](const Station& st) {
    Vec3 y = Vec3::Zero();
    for (std::size_t i = 0; i < x.size(); ++i) y += st.phi[i] * x[i];
    return y;
  };
  if (!target->deformable()) {
    for (const Station& st : face_rule(face))
      points.push_back(std::make_unique<RigidGaussPoint>(family, record.id, target->pilot(),
                                                         corners, position(st), st.phi, target,
                                                         reach, offset, law_at(st)));
    return points;
  }
  const SegmentFacets& facets = segment_facets(ctx, record.real);
  double radius = 0.0;
  for (const Vec3& y : x) radius = std::max(radius, (y - face.centre).norm());
  std::vector<Station> stations = cells(
      face, facets,
      candidate_facets(*target, facets, face.centre, reach + radius, corners, face.normal), area);
  if (stations.empty()) stations = face_rule(face);  // no overlap at setup: Gauss-point search
  for (const Station& st : stations) {
    const Vec3 xs = position(st);
    std::vector<int> near = candidate_facets(*target, facets, xs, reach, corners, face.normal);
    if (st.facet >= 0 && std::find(near.begin(), near.end(), st.facet) == near.end())
      near.insert(near.begin(), st.facet);
    std::vector<int> nodes = corners;
    std::vector<Vec3> at = x;
    std::vector<SegmentCandidate> local;
    int current = 0;
    // The facets that may share an edge with a candidate: within the pinball plus the facets'
    // extent (any orientation).
    double extent = 0.0;
    for (int f : near)
      for (const Vec3& y : facets.facets[static_cast<std::size_t>(f)].x)
        extent = std::max(extent, (y - facets.facets[static_cast<std::size_t>(f)].x[0]).norm());
    const std::vector<int> around = all_facets_near(*target, facets, xs, reach + extent);
    for (int f : near) {
      if (f == st.facet) current = static_cast<int>(local.size());
      const std::vector<int>& fn = facets.facets[static_cast<std::size_t>(f)].nodes;
      SegmentCandidate cand;
      for (int n : fn) {
        auto it = std::find(nodes.begin(), nodes.end(), n);
        if (it == nodes.end()) {
          nodes.push_back(n);
          at.push_back(model.nodes.at(n).x);
          it = nodes.end() - 1;
        }
        cand.local.push_back(static_cast<int>(it - nodes.begin()));
      }
      for (std::size_t e = 0; e < fn.size(); ++e) {
        const int a = fn[e], b = fn[(e + 1) % fn.size()];
        for (int g : around) {
          const std::vector<int>& gn = facets.facets[static_cast<std::size_t>(g)].nodes;
          if (g == f || std::find(gn.begin(), gn.end(), a) == gn.end() ||
              std::find(gn.begin(), gn.end(), b) == gn.end())
            continue;
          const bool candidate = std::find(near.begin(), near.end(), g) != near.end();
          cand.edge[e] = candidate ? 1 : std::max(cand.edge[e], 2);
        }
      }
      local.push_back(std::move(cand));
    }
    points.push_back(std::make_unique<SegmentPoint>(
        family, record.id, std::move(nodes), std::move(at), face.k(), st.phi, std::move(local),
        current, reach, offset, law_at(st)));
  }
  return points;
}

}  // namespace impactfe
