#pragma once
/// A contact element made of contact points (elements/contact_point.h): CONTA174 (one point per
/// face corner node, or per integration point segment to segment) and CONTA171/172 (one per
/// distinct node of the line). Its DOFs are the union of the points' DOFs; status, commit,
/// history and results go to each point, and large sliding refreshes each point's DOF list
/// (elements/connectivity.h).
#include <fmt/format.h>

#include <algorithm>
#include <memory>
#include <vector>

#include "core/errors.h"
#include "elements/connectivity.h"
#include "elements/contact_point.h"
#include "elements/penetration_check.h"

namespace impactfe {

class ContactPointSet final : public Element, public ConnectivityUpdate, public PenetrationCheck {
 public:
  /// No strain of its own: a thermal expansion of its material does not act on it (MAPDL
  /// applies thermal strain to the structural solids, shells, beams and links only).
  void thermal_load(const ElementContext&, Eigen::VectorXd& f) const override {
    f.setZero(n_dofs());
  }
  /// `family` and `name` (the element type's name, for messages) outlive the element.
  ContactPointSet(int id, const char* family, const char* name,
                  std::vector<std::unique_ptr<ContactPoint>> points)
      : Element(id), family_(family), name_(name), points_(std::move(points)) {
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
  const char* family() const override { return family_; }
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
                   fmt::format("{} element {}: a saved state of {} values, {} expected", name_,
                               id(), state.size(), n * points_.size()));
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

  const char* family_;
  const char* name_;
  std::vector<DofKey> dofs_;
  std::vector<std::unique_ptr<ContactPoint>> points_;
  std::vector<std::vector<int>> maps_;  // point DOF → element DOF
};

}  // namespace impactfe
