/// CONTA174 surface contact against a TARGE170 target (APDL_MODELING §8.4), rigid (pilot) or
/// deformable (large or small sliding, docs/elements/targe170.md). KEYOPT(4) selects the
/// detection as MAPDL does: 0 (the default, Gauss points) and 3 (surface projection) integrate
/// the contact pressure over the face, segment to segment (elements/contact_segment.h); 1 and 2
/// detect at the corner nodes: each distinct corner node is a contact point of CONTA175's law
/// (elements/target_surface.h target_point: penalty / augmented Lagrange, Coulomb friction,
/// KEYOPT(12)) against the target of the element's real set. Either way the element is a set of
/// ContactPoints and its DOFs are the union of theirs.
///
/// Stiffness per node: the face's tributary area of the node, a = A/n (A the face area, n its
/// corner count — the lumped nodal weights of a bilinear face). A positive FKN scales the
/// stiffness attached to the node by a / Σa, the sum over the CONTA174 elements of the same TYPE
/// and REAL at that node, so a node shared by several faces carries in total exactly the
/// stiffness a CONTA175 at that node would (the same answer as CONTA175 on the same nodes); a
/// negative FKN is MAPDL's absolute force/length³, times a. Segment to segment, the face's
/// stiffness per area is Σ k_node / A, times each integration point's weight. Midside nodes
/// (8-node faces) are not supported.
#include <fmt/format.h>

#include <Eigen/Dense>
#include <algorithm>
#include <cmath>

#include "elements/contact_segment.h"
#include "elements/element_build_cache.h"
#include "elements/element_registry.h"
#include "elements/line_element_data.h"
#include "elements/target_surface.h"

namespace impactfe {

namespace {

constexpr const char* kSurfaceContactFamily = "SurfaceContact";

/// Distinct corner nodes (the first four positions; E repeats the last node of a short list).
std::vector<int> corners(const ElementRecord& record) {
  std::vector<int> out;
  for (std::size_t k = 0; k < std::min<std::size_t>(4, record.nodes.size()); ++k)
    if (std::find(out.begin(), out.end(), record.nodes[k]) == out.end())
      out.push_back(record.nodes[k]);
  return out;
}

/// Area of the face through `nodes` (a triangle, or a quadrilateral from its diagonals).
double face_area(const Model& model, const std::vector<int>& nodes) {
  std::vector<Vec3> x;
  for (int n : nodes) x.push_back(model.nodes.at(n).x);
  if (x.size() == 3) return 0.5 * (x[1] - x[0]).cross(x[2] - x[0]).norm();
  return 0.5 * (x[2] - x[0]).cross(x[3] - x[1]).norm();
}

class SurfaceContact final : public Element, public ConnectivityUpdate, public PenetrationCheck {
 public:
  /// No strain of its own: a thermal expansion of its material does not act on it (MAPDL
  /// applies thermal strain to the structural solids, shells, beams and links only).
  void thermal_load(const ElementContext&, Eigen::VectorXd& f) const override {
    f.setZero(n_dofs());
  }
  explicit SurfaceContact(int id, std::vector<std::unique_ptr<ContactPoint>> points)
      : Element(id), points_(std::move(points)) {
    map_points();
  }
  /// Large sliding on a deformable target: the points' DOF lists, then the union again.
  bool refresh_dofs(const Eigen::VectorXd& u, const NodePositions& positions) override {
    bool changed = false;
    for (std::size_t p = 0; p < points_.size(); ++p)
      if (auto* c = dynamic_cast<ConnectivityUpdate*>(points_[p].get()))
        changed = c->refresh_dofs(local(u, p), positions) || changed;
    if (changed) map_points();
    return changed;
  }
  /// dofs_ (the union of the points' DOFs) and maps_.
  void map_points() {
    dofs_.clear();
    maps_.clear();
    for (const auto& p : points_) {
      std::vector<int> map;
      for (const DofKey& k : p->dofs()) {
        auto it = std::find_if(dofs_.begin(), dofs_.end(),
                               [&](const DofKey& d) { return d.node == k.node && d.dof == k.dof; });
        if (it == dofs_.end()) it = dofs_.insert(dofs_.end(), k);
        map.push_back(static_cast<int>(it - dofs_.begin()));
      }
      maps_.push_back(std::move(map));
    }
  }
  const char* family() const override { return kSurfaceContactFamily; }
  const std::vector<DofKey>& dofs() const override { return dofs_; }
  bool is_nonlinear(const ElementContext&) const override { return true; }

  void tangent(const ElementContext& ctx, const Eigen::VectorXd& u, Eigen::MatrixXd& K,
               Eigen::VectorXd& f_int) const override {
    K.setZero(n_dofs(), n_dofs());
    f_int.setZero(n_dofs());
    Eigen::MatrixXd k;
    Eigen::VectorXd f;
    for (std::size_t p = 0; p < points_.size(); ++p) {
      points_[p]->tangent(ctx, local(u, p), k, f);
      const std::vector<int>& m = maps_[p];
      for (std::size_t a = 0; a < m.size(); ++a) {
        f_int(m[a]) += f(static_cast<Eigen::Index>(a));
        for (std::size_t b = 0; b < m.size(); ++b)
          K(m[a], m[b]) += k(static_cast<Eigen::Index>(a), static_cast<Eigen::Index>(b));
      }
    }
  }
  void mass(const ElementContext&, Eigen::MatrixXd& M) const override {
    M.setZero(n_dofs(), n_dofs());
  }

  bool has_status() const override { return true; }
  bool checks_penetration() const override {
    return std::any_of(points_.begin(), points_.end(),
                       [](const auto& p) { return p->checks_penetration(); });
  }
  double penetration_ratio(const Eigen::VectorXd& start, const Eigen::VectorXd& u) const override {
    double worst = 0.0;
    for (std::size_t p = 0; p < points_.size(); ++p)
      worst = std::max(worst, points_[p]->penetration_ratio(local(start, p), local(u, p)));
    return worst;
  }
  /// The points' committed states, one after the other (ContactPoint::kStateSize each).
  std::vector<double> history_state() const override {
    std::vector<double> state;
    for (const auto& p : points_) {
      const std::vector<double> s = p->history_state();
      state.insert(state.end(), s.begin(), s.end());
    }
    return state;
  }
  void restore_history_state(const std::vector<double>& state) override {
    constexpr std::size_t n = ContactPoint::kStateSize;
    IMPACTFE_CHECK(state.size() == n * points_.size(),
                   fmt::format("CONTA174 element {}: a saved state of {} values, {} expected", id(),
                               state.size(), n * points_.size()));
    for (std::size_t p = 0; p < points_.size(); ++p)
      points_[p]->restore_history_state(
          std::vector<double>(state.begin() + static_cast<std::ptrdiff_t>(n * p),
                              state.begin() + static_cast<std::ptrdiff_t>(n * (p + 1))));
  }
  bool update_status(const ElementContext& ctx, const Eigen::VectorXd& u) override {
    bool changed = false;
    for (std::size_t p = 0; p < points_.size(); ++p)
      changed = points_[p]->update_status(ctx, local(u, p)) || changed;
    return changed;
  }
  void commit(const Eigen::VectorXd& u) override {
    for (std::size_t p = 0; p < points_.size(); ++p) points_[p]->commit(local(u, p));
  }
  void revert() override {
    for (auto& p : points_) p->revert();
  }
  void freeze_status(bool frozen) override {
    for (auto& p : points_) p->freeze_status(frozen);
  }
  /// Sliding when a point slides, else closed when a point is closed, else open.
  GapStatus status() const override {
    GapStatus s = GapStatus::Open;
    for (const auto& p : points_) {
      const GapStatus q = p->status();
      if (q == GapStatus::Sliding) return q;
      if (q == GapStatus::Closed) s = q;
    }
    return s;
  }
  double contact_stiffness() const override {
    double k = 0.0;
    for (const auto& p : points_) k += p->contact_stiffness();
    return k;
  }

  const std::vector<std::string>& result_names() const override { return ContactPoint::names(); }
  /// Over the points: STAT the largest (3 sticking > 2 sliding > 0 open), FN and FT the sums,
  /// PENE the largest, GAP the smallest, SLIDE the largest.
  void results(const ElementContext& ctx, const Eigen::VectorXd& u, const Eigen::VectorXd& v,
               ElementResultValues& out) const override {
    ElementResultValues r;
    for (std::size_t p = 0; p < points_.size(); ++p) {
      points_[p]->results(ctx, local(u, p), local(v, p), r);
      if (p == 0) {
        out = r;
        continue;
      }
      out[0] = std::max(out[0], r[0]);
      out[1] += r[1];
      out[2] = std::max(out[2], r[2]);
      out[3] = std::min(out[3], r[3]);
      out[4] += r[4];
      out[5] = std::max(out[5], r[5]);
    }
  }

 private:
  /// The DOFs of point p out of the element's.
  Eigen::VectorXd local(const Eigen::VectorXd& u, std::size_t p) const {
    const std::vector<int>& m = maps_[p];
    Eigen::VectorXd out(static_cast<Eigen::Index>(m.size()));
    for (std::size_t a = 0; a < m.size(); ++a) out(static_cast<Eigen::Index>(a)) = u(m[a]);
    return out;
  }

  std::vector<DofKey> dofs_;
  std::vector<std::unique_ptr<ContactPoint>> points_;
  std::vector<std::vector<int>> maps_;  // point DOF → element DOF
};

std::unique_ptr<Element> make_surface_contact(const ElementBuildContext& ctx,
                                              const ElementRecord& record) {
  const Model& model = ctx.model;
  const auto fail = [&](const std::string& what) {
    return InputError(record.where, fmt::format("element {} (CONTA174): {}", record.id, what));
  };
  for (std::size_t k = 0; k < record.nodes.size(); ++k)
    line_data::node(model, record, k, record.nodes.size(), kSurfaceContactFamily);
  const std::vector<int> nodes = corners(record);
  for (std::size_t k = 4; k < record.nodes.size(); ++k)
    if (std::find(nodes.begin(), nodes.end(), record.nodes[k]) == nodes.end())
      throw fail(
          "midside nodes (8-node faces) are not supported: give the 3 or 4 corner nodes "
          "(E,I,J,K,L) or generate the elements with ESURF on linear elements");
  if (nodes.size() < 3) throw fail("a contact face needs 3 or 4 distinct corner nodes");
  const double area = face_area(model, nodes);
  if (!(area > 0.0)) throw fail("degenerate contact face (zero area)");
  const double tributary = area / static_cast<double>(nodes.size());

  std::vector<std::unique_ptr<ContactPoint>> points;
  for (int n : nodes) {
    // Σ of the tributary areas at n over the CONTA174 faces of this TYPE and REAL.
    double total = 0.0;
    for (const int id : elements_at_node(ctx, n)) {
      const ElementRecord& other = model.elements.at(id);
      if (other.type != record.type || other.real != record.real) continue;
      const std::vector<int> c = corners(other);
      if (c.size() < 3 || std::find(c.begin(), c.end(), n) == c.end()) continue;
      total += face_area(model, c) / static_cast<double>(c.size());
    }
    const Node& node = model.nodes.at(n);
    points.push_back(target_point(ctx, record, node, kSurfaceContactFamily, "CONTA174",
                                  tributary / std::max(total, tributary), tributary));
  }
  // KEYOPT(4) = 0 (MAPDL's default, Gauss-point detection) and 3 (surface-projection based):
  // segment-to-segment integration over the face (elements/contact_segment.h); 1 and 2: nodal.
  const int detection = line_data::element_type(model, record).key(4);
  if (detection == 0 || detection == 3)
    points = segment_points(ctx, record, nodes, points, kSurfaceContactFamily);
  return std::make_unique<SurfaceContact>(record.id, std::move(points));
}

const ElementRegistration kConta174{{.name = "CONTA174",
                                     .number = 174,
                                     .family = kSurfaceContactFamily,
                                     .n_nodes = 8,
                                     .min_nodes = 3,
                                     .real_constants = RealConstantUse::Required,
                                     .vtk_cell = VtkCell::Quad,
                                     .role = ShapeRole::Contact,
                                     .result_names = ContactPoint::names(),
                                     .result_sequences = ContactPoint::sequences(),
                                     .has_status = true,
                                     .create = make_surface_contact}};

}  // namespace

}  // namespace impactfe
