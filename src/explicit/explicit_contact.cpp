#include "explicit/explicit_contact.h"

#include <fmt/format.h>

#include <algorithm>
#include <array>
#include <cmath>
#include <limits>
#include <map>
#include <tuple>

#include "core/numbers.h"
#include "explicit/part_energies.h"

namespace impactfe {

namespace {

constexpr double kXi[4] = {-1, 1, 1, -1}, kEta[4] = {-1, -1, 1, 1};
/// A projection this far outside [−1, 1]² still counts as on the segment (a node on the edge
/// between two segments is not lost between them).
constexpr double kEdgeTolerance = 1e-3;
/// No segment (a slave out of contact).
constexpr std::size_t kNone = std::numeric_limits<std::size_t>::max();

struct Vec {
  double x, y, z;
};
Vec sub(Vec a, Vec b) {
  return {a.x - b.x, a.y - b.y, a.z - b.z};
}
Vec cross(Vec a, Vec b) {
  return {a.y * b.z - a.z * b.y, a.z * b.x - a.x * b.z, a.x * b.y - a.y * b.x};
}
double dot(Vec a, Vec b) {
  return a.x * b.x + a.y * b.y + a.z * b.z;
}

/// The point X(ξ, η) of the bilinear segment `p` and its tangents ∂X/∂ξ, ∂X/∂η.
void surface_point(const Vec p[4], double xi, double eta, Vec& x, Vec& dxi, Vec& deta) {
  x = dxi = deta = {0, 0, 0};
  for (int a = 0; a < 4; ++a) {
    const double n = 0.25 * (1 + kXi[a] * xi) * (1 + kEta[a] * eta);
    const double nx = 0.25 * kXi[a] * (1 + kEta[a] * eta);
    const double ne = 0.25 * kEta[a] * (1 + kXi[a] * xi);
    x = {x.x + n * p[a].x, x.y + n * p[a].y, x.z + n * p[a].z};
    dxi = {dxi.x + nx * p[a].x, dxi.y + nx * p[a].y, dxi.z + nx * p[a].z};
    deta = {deta.x + ne * p[a].x, deta.y + ne * p[a].y, deta.z + ne * p[a].z};
  }
}

/// The local coordinates (ξ, η) of the point of the bilinear segment `p` nearest to `q`:
/// Gauss–Newton on X(ξ, η) − q (three steps: the segments are close to flat).
void local_coordinates(const Vec p[4], Vec q, double& xi, double& eta) {
  xi = eta = 0.0;
  for (int it = 0; it < 4; ++it) {
    Vec x, dxi, deta;
    surface_point(p, xi, eta, x, dxi, deta);
    const Vec r = sub(q, x);
    const double a11 = dot(dxi, dxi), a12 = dot(dxi, deta), a22 = dot(deta, deta);
    const double b1 = dot(dxi, r), b2 = dot(deta, r);
    const double det = a11 * a22 - a12 * a12;
    if (!(std::abs(det) > 0.0)) return;
    xi += (a22 * b1 - a12 * b2) / det;
    eta += (a11 * b2 - a12 * b1) / det;
  }
}

/// The factor on a contact spring's stable step 2/ω for its viscous damping of ξ of critical:
/// the central difference with the damping force from v(n+1/2) is stable for
/// ω dt ≤ 2(√(1 + ξ²) − ξ) (Belytschko, Liu & Moran, Nonlinear Finite Elements, eq. (6.3.28)).
double damped_step_factor(const ExplicitContact& k) {
  const double xi = 0.01 * k.viscous_damping;
  return std::sqrt(1.0 + xi * xi) - xi;
}

/// The penetration of the slave at `xs` behind the segment on `nodes` (of depth `depth`): false
/// when it is not behind it (or deeper than the segment's depth) or does not project onto it.
/// `gap` is set once the slave is found behind the face's plane (a slave that slid off its
/// segment is told by it). `side` (±1) turns the face's normal: a shell is touched from either
/// side. `offset` is how far in front of the face the contact surface lies: half the thickness
/// of a shell segment plus half that of a shell slave node, 0 between solids.
bool behind_segment(const int nodes[4], double depth, double offset, double side,
                    const ExplicitNodalView& s, Vec xs, double& gap, double& u, double& v,
                    Vec& nrm) {
  Vec q[4], centre{0, 0, 0};
  for (int a = 0; a < 4; ++a) {
    const auto n = static_cast<std::size_t>(nodes[a]);
    q[a] = {s.x[n], s.y[n], s.z[n]};
    centre = {centre.x + 0.25 * q[a].x, centre.y + 0.25 * q[a].y, centre.z + 0.25 * q[a].z};
  }
  // The face's plane (normal from the diagonals) rules out what lies far from it.
  const Vec plane = cross(sub(q[2], q[0]), sub(q[3], q[1]));
  const double len = std::sqrt(dot(plane, plane));
  if (!(len > 0.0)) return false;
  const double across = offset - side * dot(sub(xs, centre), plane) / len;
  if (!(across > 0.0) || across > 2.0 * (depth + offset)) return false;
  gap = across - 1e-4 * depth;  // off the face: how far behind its plane
  local_coordinates(q, xs, u, v);
  if (!(std::abs(u) <= 1 + kEdgeTolerance && std::abs(v) <= 1 + kEdgeTolerance)) return false;
  // The gap at the point X(ξ, η) of the bilinear face the slave projects onto, along the
  // face's normal there: g = offset − (x_s − X)·n. Its change with a node of the face is N_a n,
  // the shares the reaction is spread by, so the force is the gradient of ½kg² and the
  // springs give back what they took. The gap from the centroid's plane instead changes
  // by ¼ n with each corner: on a warped face (the dished face under an impactor) the
  // reaction on a corner a slave sits on did four times the work of the spring.
  Vec x, dxi, deta;
  surface_point(q, std::clamp(u, -1.0, 1.0), std::clamp(v, -1.0, 1.0), x, dxi, deta);
  nrm = cross(dxi, deta);
  const double size = std::sqrt(dot(nrm, nrm));
  if (!(size > 0.0)) return false;
  nrm = {side * nrm.x / size, side * nrm.y / size, side * nrm.z / size};
  // Penetration behind the face, less a sliver (1e-4 of the depth): a node on the edge of a
  // face it runs along (the side of a body it hits end on) has round-off penetrations of
  // that side, smaller than its true one; taking the smallest would pick the side.
  gap = offset - dot(sub(xs, x), nrm) - 1e-4 * depth;
  return gap > 0.0 && gap <= depth + offset;
}

/// The slave `sn` (at `xs` now) at x_n = x_{n+1} − step v_{n+1/2}, seen from the segment on
/// `nodes` then: its distance in front of the face's plane along the (unturned) normal.
double distance_before(const int nodes[4], const ExplicitNodalView& s, std::size_t sn, Vec xs,
                       double step) {
  Vec q[4], centre{0, 0, 0};
  for (int a = 0; a < 4; ++a) {
    const auto n = static_cast<std::size_t>(nodes[a]);
    q[a] = {s.x[n] - step * s.vx[n], s.y[n] - step * s.vy[n], s.z[n] - step * s.vz[n]};
    centre = {centre.x + 0.25 * q[a].x, centre.y + 0.25 * q[a].y, centre.z + 0.25 * q[a].z};
  }
  const Vec nrm = cross(sub(q[2], q[0]), sub(q[3], q[1]));
  const double len = std::sqrt(dot(nrm, nrm));
  if (!(len > 0.0)) return 0.0;
  const Vec xp{xs.x - step * s.vx[sn], xs.y - step * s.vy[sn], xs.z - step * s.vz[sn]};
  return dot(sub(xp, centre), nrm) / len;
}

/// Viscous contact damping VDC (LS-DYNA Theory Manual, "Contact damping"): the force −c·v_n
/// along the normal, c = VDC/100 · 2mω, m = min(m_s, m_m), ω² = k(m_s + m_m)/(m_s m_m), m_m the
/// segment's mass at the projection (Σ N_a m_a). The normal force stays ≥ 0: the damping slows
/// a separation, it never holds the bodies together.
double damped_normal_force(const ExplicitContact& k, double fn, double vn, double stiffness,
                           const double shape[4], const int nodes[4], const double* mass,
                           std::size_t sn) {
  double m_master = 0.0;
  for (int a = 0; a < 4; ++a) m_master += shape[a] * mass[static_cast<std::size_t>(nodes[a])];
  const double m_slave = mass[sn];
  if (m_slave > 0.0 && m_master > 0.0) {
    const double omega = std::sqrt(stiffness * (m_slave + m_master) / (m_slave * m_master));
    const double c = 0.02 * k.viscous_damping * std::min(m_slave, m_master) * omega;
    fn = std::max(0.0, fn - c * vn);
  }
  return fn;
}

/// Elastic-slip friction: the tangential spring `ft` (stiffness k) loaded by the relative
/// tangential motion dt·v_t, its force bounded by μ f_n, μ = FD + (FS − FD) e^{−DC|v_t|}. Returns
/// the spring's force; adds its energy to `stored`.
Vec elastic_slip_friction(const ExplicitContact& k, double* ft, Vec vr, double vn, Vec normal,
                          double stiffness, double fn, double dt, double& stored) {
  const double mu_s = k.static_friction, mu_d = k.dynamic_friction;
  const Vec vt{vr.x - vn * normal.x, vr.y - vn * normal.y, vr.z - vn * normal.z};
  const double speed = std::sqrt(dot(vt, vt));
  const double mu = mu_d + (mu_s - mu_d) * std::exp(-k.decay * speed);
  Vec t{ft[0], ft[1], ft[2]};
  const double tn = dot(t, normal);
  t = {t.x - tn * normal.x - stiffness * dt * vt.x, t.y - tn * normal.y - stiffness * dt * vt.y,
       t.z - tn * normal.z - stiffness * dt * vt.z};
  const double size = std::sqrt(dot(t, t)), bound = mu * fn;
  if (size > bound) t = {t.x * bound / size, t.y * bound / size, t.z * bound / size};
  ft[0] = t.x, ft[1] = t.y, ft[2] = t.z;
  stored += 0.5 * dot(t, t) / stiffness;
  return t;
}

}  // namespace

struct ExplicitContactSet::Projection {
  double gap;           // penetration behind the segment
  double xi, eta;       // the slave's local coordinates on it
  std::size_t segment;  // index into segments_
  double normal[3];     // the segment's unit normal there
};

ExplicitContactSet::ExplicitContactSet(const Model& model, const ExplicitSystem& system) {
  const auto& definitions = model.explicit_dynamics.contacts;
  if (definitions.empty()) return;
  collect_segments(system);
  const std::map<int, int> part = explicit_part_numbers(model);
  const double slsfac = model.explicit_dynamics.penalty_factor;
  interface_force_.assign(3 * definitions.size(), 0.0);
  for (std::size_t entity = 0; entity < definitions.size(); ++entity) {
    const ExplicitContact& k = definitions[entity];
    const bool single = k.option == "ASSC" || k.option == "SS";
    const bool symmetric = k.option == "STS" || k.option == "ASTS";
    std::vector<std::size_t> cont_segs, cont_nodes, targ_segs, targ_nodes;
    // single surface: blank is the whole model
    surface(model, system, part, k, k.contact, cont_segs, cont_nodes);
    if (!single) surface(model, system, part, k, k.target, targ_segs, targ_nodes);
    // The interface force counts what acts on the contact surface: its own slaves' forces (+1)
    // and the reactions on its segments of the reverse pass (−1); none for a single surface.
    if (single) {
      add_pass(k, slsfac * k.slave_scale, single, cont_nodes, cont_segs, system.n_nodes(), entity,
               0.0);
      for (int i = 0; i < 3; ++i) interface_force_[3 * entity + i] = kNaN;
    } else {
      add_pass(k, slsfac * k.master_scale, single, cont_nodes, targ_segs, system.n_nodes(), entity,
               1.0);
      if (symmetric)
        add_pass(k, slsfac * k.slave_scale, single, targ_nodes, cont_segs, system.n_nodes(), entity,
                 -1.0);
    }
  }
  force_.assign(3 * system.n_nodes(), 0.0);
  stiffness_.assign(system.n_nodes(), 0.0);
  previous_ = force_;
  mark_.assign(system.n_nodes(), 0);
}

void ExplicitContactSet::collect_segments(const ExplicitSystem& system) {
  // Every element's faces; a face offered twice (by two elements) is interior.
  std::vector<ExplicitSegment> all;
  node_offset_.assign(system.n_nodes(), 0.0);
  for (const auto& set : system.sets) set->segments(all);
  for (const auto& set : system.rigid_sets) set->segments(all);  // rigid bodies' faces too
  std::map<std::array<int, 4>, int> count;
  const auto key = [](const ExplicitSegment& s) {
    std::array<int, 4> k{s.nodes[0], s.nodes[1], s.nodes[2], s.nodes[3]};
    std::sort(k.begin(), k.end());
    return k;
  };
  for (const auto& s : all)
    if (s.thickness == 0.0) ++count[key(s)];
  double depth_max = 0.0;
  for (const auto& s : all) {
    if (s.thickness == 0.0 && count[key(s)] > 1) continue;
    Vec p[4];
    for (int a = 0; a < 4; ++a) {
      const auto n = static_cast<std::size_t>(s.nodes[a]);
      p[a] = {system.x0[n], system.y0[n], system.z0[n]};
    }
    const Vec normal = cross(sub(p[2], p[0]), sub(p[3], p[1]));
    const double area = 0.5 * std::sqrt(dot(normal, normal));
    if (!(area > 0.0)) continue;  // a face collapsed to an edge or a point
    Segment g{};
    std::copy(s.nodes, s.nodes + 4, g.nodes);
    g.element = s.element;
    if (s.thickness > 0.0) {
      // Shell: k = f·K·A / (largest diagonal) (LS-DYNA Theory Manual, penalty method). Its
      // surfaces lie half the thickness off the mid-surface on either side; a slave is held
      // until it reaches the far one (depth: the thickness).
      const double diagonal = std::sqrt(
          std::max(dot(sub(p[2], p[0]), sub(p[2], p[0])), dot(sub(p[3], p[1]), sub(p[3], p[1]))));
      g.stiffness = s.bulk_modulus * area / diagonal;
      g.depth = s.thickness;
      g.offset = 0.5 * s.thickness;
      for (int a = 0; a < 4; ++a) {
        double& r = node_offset_[static_cast<std::size_t>(s.nodes[a])];
        r = std::max(r, g.offset);
      }
    } else {
      // Solid: k = f·K·A²/V; a node deeper than half the element (V/A) behind the face has not
      // come through it (single surface: it belongs to the same body).
      g.stiffness = s.bulk_modulus * area * area / s.volume;
      g.depth = 0.5 * s.volume / area;
    }
    depth_max = std::max(depth_max, g.depth + 2.0 * g.offset);
    segments_.push_back(g);
  }
  margin_ = 2.0 * depth_max;
}

void ExplicitContactSet::surface(const Model& model, const ExplicitSystem& system,
                                 const std::map<int, int>& part, const ExplicitContact& k,
                                 const std::string& name, std::vector<std::size_t>& segs,
                                 std::vector<std::size_t>& nodes) const {
  std::vector<std::uint8_t> in_node(system.n_nodes(), 0);
  const Component* component = nullptr;
  int part_number = 0;
  if (!name.empty()) {
    const auto it = model.components.find(name);
    if (it != model.components.end()) {
      component = &it->second;
      if (component->entity != "NODE" && component->entity != "ELEM")
        throw InputError(k.where, fmt::format("EDCGEN: component {} is a {} component; contact "
                                              "takes a node or element component",
                                              name, component->entity));
    } else {
      char* end = nullptr;
      part_number = static_cast<int>(std::strtol(name.c_str(), &end, 10));
      if (*end != '\0' || part_number <= 0)
        throw InputError(k.where, fmt::format("EDCGEN: '{}' is neither a component (CM) nor a "
                                              "part number (EDPART)",
                                              name));
    }
  }
  if (component && component->entity == "NODE")
    for (int id : component->ids)
      if (const int n = system.index_of(id); n >= 0) in_node[static_cast<std::size_t>(n)] = 1;
  for (std::size_t i = 0; i < segments_.size(); ++i) {
    const Segment& g = segments_[i];
    bool take = true;
    if (part_number > 0) {
      take = part.at(g.element) == part_number;
    } else if (component && component->entity == "ELEM") {
      take = std::binary_search(component->ids.begin(), component->ids.end(), g.element);
    } else if (component) {
      for (int a = 0; a < 4; ++a) take = take && in_node[static_cast<std::size_t>(g.nodes[a])];
    }
    if (take) segs.push_back(i);
  }
  std::vector<std::uint8_t> slave(system.n_nodes(), 0);
  if (component && component->entity == "NODE")
    slave = in_node;
  else
    for (std::size_t i : segs)
      for (int a = 0; a < 4; ++a) slave[static_cast<std::size_t>(segments_[i].nodes[a])] = 1;
  for (std::size_t n = 0; n < system.n_nodes(); ++n)
    if (slave[n]) nodes.push_back(n);
  if (segs.empty() && nodes.empty())
    throw InputError(k.where, fmt::format("EDCGEN,{}: '{}' has no exterior face or node of an "
                                          "explicit element",
                                          k.option, name.empty() ? "the model" : name));
}

void ExplicitContactSet::add_pass(const ExplicitContact& k, double factor, bool single,
                                  std::vector<std::size_t> slaves, std::vector<std::size_t> segs,
                                  std::size_t n_nodes, std::size_t entity, double side) {
  if (segs.empty())
    throw InputError(k.where, fmt::format("EDCGEN,{}: the target surface has no exterior "
                                          "face of an explicit element (a node component "
                                          "names its faces by all their nodes)",
                                          k.option));
  Pass p;
  p.definition = &k;
  p.entity = entity;
  p.interface_side = side;
  p.factor = factor;
  p.single_surface = single;
  p.slaves = std::move(slaves);
  p.segments = std::move(segs);
  p.tangential.assign(3 * p.slaves.size(), 0.0);
  p.kept.assign(p.slaves.size(), kNone);
  p.side.assign(p.slaves.size(), 1);
  if (single) list_near_nodes(p, n_nodes);
  passes_.push_back(std::move(p));
}

void ExplicitContactSet::list_near_nodes(Pass& p, std::size_t n_nodes) const {
  // The nodes of the segments around each slave: a slave is not checked against a segment
  // that shares one of them (its own body's neighbouring faces).
  std::vector<std::vector<int>> near(n_nodes);
  for (std::size_t i : p.segments)
    for (int a = 0; a < 4; ++a)
      for (int b = 0; b < 4; ++b)
        near[static_cast<std::size_t>(segments_[i].nodes[a])].push_back(segments_[i].nodes[b]);
  p.near_start.push_back(0);
  for (std::size_t s : p.slaves) {
    auto& list = near[s];
    std::sort(list.begin(), list.end());
    list.erase(std::unique(list.begin(), list.end()), list.end());
    p.near.insert(p.near.end(), list.begin(), list.end());
    p.near_start.push_back(p.near.size());
  }
}

void ExplicitContactSet::search(Pass& p, const ExplicitNodalView& s) const {
  // Bucket sort: each segment's box, inflated by the margin, goes into the cells of a grid as
  // fine as the largest box; a slave's candidates are the segments of its cell whose box holds
  // it. Sorted (cell, segment) pairs keep the candidate order fixed.
  struct Box {
    double lo[3], hi[3];
  };
  std::vector<Box> boxes(p.segments.size());
  double cell = 0.0;
  for (std::size_t i = 0; i < p.segments.size(); ++i) {
    const Segment& g = segments_[p.segments[i]];
    Box& b = boxes[i];
    for (int d = 0; d < 3; ++d)
      b.lo[d] = std::numeric_limits<double>::infinity(), b.hi[d] = -b.lo[d];
    for (int a = 0; a < 4; ++a) {
      const auto n = static_cast<std::size_t>(g.nodes[a]);
      const double c[3] = {s.x[n], s.y[n], s.z[n]};
      for (int d = 0; d < 3; ++d)
        b.lo[d] = std::min(b.lo[d], c[d]), b.hi[d] = std::max(b.hi[d], c[d]);
    }
    for (int d = 0; d < 3; ++d) {
      b.lo[d] -= margin_;
      b.hi[d] += margin_;
      cell = std::max(cell, b.hi[d] - b.lo[d]);
    }
  }
  const auto index = [cell](double v) { return static_cast<long long>(std::floor(v / cell)); };
  const auto cell_key = [](long long i, long long j, long long k) {
    // 21 bits per axis (offset): the grid of one model never spans 2^21 cells of its largest box.
    constexpr long long kOffset = 1LL << 20;
    return ((i + kOffset) << 42) | ((j + kOffset) << 21) | (k + kOffset);
  };
  std::vector<std::pair<long long, std::size_t>> cells;
  for (std::size_t i = 0; i < boxes.size(); ++i) {
    const Box& b = boxes[i];
    for (long long a = index(b.lo[0]); a <= index(b.hi[0]); ++a)
      for (long long c = index(b.lo[1]); c <= index(b.hi[1]); ++c)
        for (long long d = index(b.lo[2]); d <= index(b.hi[2]); ++d)
          cells.emplace_back(cell_key(a, c, d), i);
  }
  std::sort(cells.begin(), cells.end());
  p.candidate_start.assign(1, 0);
  p.candidates.clear();
  for (std::size_t j = 0; j < p.slaves.size(); ++j) {
    const std::size_t n = p.slaves[j];
    const double c[3] = {s.x[n], s.y[n], s.z[n]};
    const long long k = cell_key(index(c[0]), index(c[1]), index(c[2]));
    auto it = std::lower_bound(cells.begin(), cells.end(), std::make_pair(k, std::size_t{0}));
    for (; it != cells.end() && it->first == k; ++it) {
      const Box& b = boxes[it->second];
      if (c[0] >= b.lo[0] && c[0] <= b.hi[0] && c[1] >= b.lo[1] && c[1] <= b.hi[1] &&
          c[2] >= b.lo[2] && c[2] <= b.hi[2])
        p.candidates.push_back(p.segments[it->second]);
    }
    p.candidate_start.push_back(p.candidates.size());
  }
}

bool ExplicitContactSet::search_due(const ExplicitNodalView& s) const {
  // A new search when some node may have moved by half the margin since the last one: a node
  // and a segment that approach each other then still lie within their listed boxes.
  if (!started_) return true;
  double moved = 0.0;
  for (std::size_t n = 0; n < x_search_.size(); ++n) {
    const double dx = s.x[n] - x_search_[n], dy = s.y[n] - y_search_[n], dz = s.z[n] - z_search_[n];
    moved = std::max(moved, dx * dx + dy * dy + dz * dz);
  }
  return std::sqrt(moved) > 0.25 * margin_;
}

void ExplicitContactSet::search_all(const ExplicitNodalView& s, const double* mass) {
  for (Pass& p : passes_) search(p, s);
  x_search_.assign(s.x, s.x + force_.size() / 3);
  y_search_.assign(s.y, s.y + force_.size() / 3);
  z_search_.assign(s.z, s.z + force_.size() / 3);
  started_ = true;
  ++searches_;
  // The step the contact will need once the listed pairs touch: a pair's row bound is 2k/m on
  // either side (see add_contact_force), doubled for a node that is slave in one pass and master
  // in the other. Without it the first cycle of a stiff contact would run at the elements' step.
  double omega2 = 0.0;
  potential_element_ = 0;
  for (const Pass& p : passes_)
    for (std::size_t j = 0; j < p.slaves.size(); ++j)
      for (std::size_t c = p.candidate_start[j]; c < p.candidate_start[j + 1]; ++c) {
        const Segment& g = segments_[p.candidates[c]];
        const double soften = damped_step_factor(*p.definition);
        const double k4 = 4.0 * p.factor * g.stiffness / (soften * soften);
        double w = mass[p.slaves[j]] > 0.0 ? k4 / mass[p.slaves[j]] : 0.0;
        for (int a = 0; a < 4; ++a)
          if (const double m = mass[static_cast<std::size_t>(g.nodes[a])]; m > 0.0)
            w = std::max(w, k4 / m);
        if (w > omega2) omega2 = w, potential_element_ = g.element;
      }
  potential_step_ =
      omega2 > 0.0 ? 2.0 / std::sqrt(omega2) : std::numeric_limits<double>::infinity();
}

bool ExplicitContactSet::shares_node(std::size_t a, std::size_t b) const {
  for (int i = 0; i < 4; ++i)
    for (int j = 0; j < 4; ++j)
      if (segments_[a].nodes[i] == segments_[b].nodes[j]) return true;
  return false;
}

bool ExplicitContactSet::find_contact(Pass& p, std::size_t j, const ExplicitNodalView& s, bool on,
                                      double dt, Projection& at) const {
  const std::size_t sn = p.slaves[j];
  const Vec xs{s.x[sn], s.y[sn], s.z[sn]};
  double best = std::numeric_limits<double>::infinity(), xi = 0, eta = 0;
  std::size_t chosen = 0;
  signed char side = 1;
  Vec normal{0, 0, 0};
  // A slave in contact keeps the segment it came through while it stays behind it and
  // projects onto it. Choosing afresh each cycle the smallest penetration over all the
  // segments would let it jump to a face it never crossed (at a corner of the other body,
  // the side face the slave is a round-off inside of): the spring's energy ½kg² of the face
  // it came through would vanish in one cycle, energy the contact never gives back.
  std::size_t& kept = p.kept[j];
  const std::size_t was = kept;
  bool slid = false;  // behind its segment's plane still, but no longer over it
  if (on && kept != kNone) {
    double gap = -1.0, u, v;
    Vec nrm;
    const Segment& g = segments_[kept];
    const double offset = g.offset + node_offset_[sn];
    if (behind_segment(g.nodes, g.depth, offset, p.side[j], s, xs, gap, u, v, nrm))
      best = gap, xi = u, eta = v, chosen = kept, side = p.side[j], normal = nrm;
    else
      slid = gap > 0.0 && gap <= g.depth + offset;
  }
  const bool held = best < std::numeric_limits<double>::infinity();
  for (std::size_t c = p.candidate_start[j]; on && !held && c < p.candidate_start[j + 1]; ++c) {
    const Segment& g = segments_[p.candidates[c]];
    bool skip = false;
    for (int a = 0; a < 4; ++a) {
      skip = skip || static_cast<std::size_t>(g.nodes[a]) == sn;
      if (p.single_surface)
        skip = skip || std::binary_search(p.near.begin() + p.near_start[j],
                                          p.near.begin() + p.near_start[j + 1], g.nodes[a]);
    }
    if (skip) continue;
    // The side the slave comes from: a solid's face is touched from outside (its normal), a
    // shell's from the side of its mid-surface the slave was on at the start of the step.
    // The position before the step is needed first only for a shell (its side); for a solid's
    // face only once the slave is found behind it, as the crossing test below asks.
    const bool shell = g.offset > 0.0;
    double before = shell ? distance_before(g.nodes, s, sn, xs, dt > 0.0 ? dt : 0.0) : 0.0;
    const signed char from = shell && before < 0.0 ? -1 : 1;
    const double offset = g.offset + node_offset_[sn];
    double gap, u, v;
    Vec nrm;
    if (!behind_segment(g.nodes, g.depth, offset, from, s, xs, gap, u, v, nrm) || gap >= best)
      continue;
    // A new contact is a slave that came through the contact surface over this step: it was
    // in front of it at x_n = x_{n+1} − dt v_{n+1/2}. A slave found behind a face it
    // did not cross is inside the other body through another face (near an edge: behind
    // the side face of a body whose top face it lies on) or was there at the start; a
    // spring taken up at such a penetration would give back energy it never took. A slave
    // sliding off its segment onto one sharing a node with it is handed over.
    const bool handed_over = slid && shares_node(was, p.candidates[c]);
    if (!handed_over && !shell && dt > 0.0) before = distance_before(g.nodes, s, sn, xs, dt);
    if (!handed_over && !(dt > 0.0 && from * before >= offset - 1e-4 * g.depth)) continue;
    best = gap, xi = u, eta = v, chosen = p.candidates[c], side = from, normal = nrm;
  }
  kept = best < std::numeric_limits<double>::infinity() ? chosen : kNone;
  if (!(best < std::numeric_limits<double>::infinity())) return false;
  p.side[j] = side;
  at = {best, xi, eta, chosen, {normal.x, normal.y, normal.z}};
  return true;
}

void ExplicitContactSet::touch(std::size_t n, double fx, double fy, double fz) {
  if (!mark_[n]) {
    mark_[n] = 1;
    touched_.push_back(n);
  }
  force_[3 * n] += fx;
  force_[3 * n + 1] += fy;
  force_[3 * n + 2] += fz;
}

void ExplicitContactSet::add_contact_force(Pass& p, std::size_t j, const ExplicitNodalView& s,
                                           const double* mass, double dt, const Projection& at) {
  const ExplicitContact& k = *p.definition;
  const std::size_t sn = p.slaves[j];
  const double best = at.gap;
  const Vec normal{at.normal[0], at.normal[1], at.normal[2]};
  const Segment& g = segments_[at.segment];
  double shape[4];
  Vec vm{0, 0, 0};
  for (int a = 0; a < 4; ++a) {
    shape[a] = 0.25 * (1 + kXi[a] * std::clamp(at.xi, -1.0, 1.0)) *
               (1 + kEta[a] * std::clamp(at.eta, -1.0, 1.0));
    const auto n = static_cast<std::size_t>(g.nodes[a]);
    vm = {vm.x + shape[a] * s.vx[n], vm.y + shape[a] * s.vy[n], vm.z + shape[a] * s.vz[n]};
  }
  const double stiffness = p.factor * g.stiffness;
  const Vec vr = sub({s.vx[sn], s.vy[sn], s.vz[sn]}, vm);
  const double vn = dot(vr, normal);  // > 0: separating
  double fn = stiffness * best;
  if (k.viscous_damping > 0.0)
    fn = damped_normal_force(k, fn, vn, stiffness, shape, g.nodes, mass, sn);
  Vec f{fn * normal.x, fn * normal.y, fn * normal.z};
  stored_ += 0.5 * stiffness * best * best;
  if (k.static_friction > 0.0 || k.dynamic_friction > 0.0) {
    const Vec t =
        elastic_slip_friction(k, &p.tangential[3 * j], vr, vn, normal, stiffness, fn, dt, stored_);
    f = {f.x + t.x, f.y + t.y, f.z + t.z};
  }
  touch(sn, f.x, f.y, f.z);
  if (p.interface_side != 0.0) {
    double* total = &interface_force_[3 * p.entity];
    total[0] += p.interface_side * f.x;
    total[1] += p.interface_side * f.y;
    total[2] += p.interface_side * f.z;
  }
  // Gershgorin's bound on the largest frequency of M⁻¹K_c: the pair's spring matrix
  // k[1, −N; −N, NNᵀ] has the absolute row sums 2k (slave) and 2k·N_a (masters).
  // Damping lowers the spring's stable step by damped_step_factor: as a stiffer spring.
  const double soften = damped_step_factor(k);
  const double bound = 2.0 * stiffness / (soften * soften);
  stiffness_[sn] += bound;
  for (int a = 0; a < 4; ++a) {
    touch(static_cast<std::size_t>(g.nodes[a]), -shape[a] * f.x, -shape[a] * f.y, -shape[a] * f.z);
    stiffness_[static_cast<std::size_t>(g.nodes[a])] += bound * shape[a];
  }
  if (element_ == 0) element_ = g.element;
}

void ExplicitContactSet::close_cycle(const ExplicitNodalView& s, const double* mass, double dt,
                                     ExplicitStepLimit& limit, double* fx, double* fy, double* fz) {
  // Work of the contact forces on the nodes over the step, trapezoidal: ½(f_n + f_{n+1})·dt v;
  // the contact energy is minus it (what the springs hold and friction and damping took).
  double work = 0.0;
  const double* v[3] = {s.vx, s.vy, s.vz};
  for (std::size_t n : touched_)
    for (int d = 0; d < 3; ++d)
      work += 0.5 * (previous_[3 * n + d] + force_[3 * n + d]) * dt * v[d][n];
  for (std::size_t n : touched_before_)
    if (!mark_[n])
      for (int d = 0; d < 3; ++d) work += 0.5 * previous_[3 * n + d] * dt * v[d][n];
  energy_ -= work;
  for (std::size_t n : touched_before_)
    for (int d = 0; d < 3; ++d) previous_[3 * n + d] = 0.0;
  // The contact's stable step 2/ω_c, ω_c² the largest row bound over the nodes in contact.
  double omega2 = 0.0;
  for (std::size_t n : touched_) {
    if (mass[n] > 0.0) omega2 = std::max(omega2, stiffness_[n] / mass[n]);
    stiffness_[n] = 0.0;
  }
  if (omega2 > 0.0) limit.take(2.0 / std::sqrt(omega2), element_);
  element_ = 0;
  for (std::size_t n : touched_) {
    fx[n] -= force_[3 * n];  // f_int sign: the contact force pushes the node
    fy[n] -= force_[3 * n + 1];
    fz[n] -= force_[3 * n + 2];
    for (int d = 0; d < 3; ++d) {
      previous_[3 * n + d] = force_[3 * n + d];
      force_[3 * n + d] = 0.0;
    }
    mark_[n] = 0;
  }
  touched_before_.swap(touched_);
}

ExplicitStepLimit ExplicitContactSet::add_forces(const ExplicitNodalView& s, const double* mass,
                                                 double time, double dt, double* fx, double* fy,
                                                 double* fz) {
  ExplicitStepLimit limit;
  if (passes_.empty()) return limit;
  if (search_due(s)) search_all(s, mass);
  limit.take(potential_step_, potential_element_);
  stored_ = 0.0;
  active_ = 0;
  touched_.clear();
  for (const Pass& p : passes_)
    if (p.interface_side != 0.0) std::fill_n(&interface_force_[3 * p.entity], 3, 0.0);
  for (Pass& p : passes_) {
    const ExplicitContact& k = *p.definition;
    const bool on = time >= k.birth && !(k.death > 0.0 && time > k.death);
    for (std::size_t j = 0; j < p.slaves.size(); ++j) {
      Projection at;
      if (!find_contact(p, j, s, on, dt, at)) {
        double* ft = &p.tangential[3 * j];
        ft[0] = ft[1] = ft[2] = 0.0;  // out of contact: the friction spring is released
        continue;
      }
      ++active_;
      add_contact_force(p, j, s, mass, dt, at);
    }
  }
  peak_active_ = std::max(peak_active_, active_);
  close_cycle(s, mass, dt, limit, fx, fy, fz);
  return limit;
}

std::string ExplicitContactSet::summary() const {
  std::size_t slaves = 0;
  for (const Pass& p : passes_) slaves += p.slaves.size();
  return fmt::format(
      "contact: {} passes, {} segments, {} slave nodes; {} searches; {} nodes in contact at most; "
      "energy {:.4g} (springs {:.4g}, dissipated by friction and damping {:.4g})",
      passes_.size(), segments_.size(), slaves, searches_, peak_active_, energy_, stored_,
      energy_ - stored_);
}

}  // namespace impactfe
