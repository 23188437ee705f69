#include "elements/combination_gap.h"

#include <fmt/format.h>

#include <cmath>

#include "elements/element_registry.h"
#include "elements/line_element_data.h"

namespace impactfe {

CombinationGap::CombinationGap(int id, std::vector<DofKey> dofs, const CombinationGapData& data)
    : Element(id), dofs_(std::move(dofs)), data_(data) {
  // Initial status at u = 0: closed for GAP ≤ 0 (interference or no gap), possibly sliding.
  committed_ = State{};
  trial_ = committed_;
  trial_ = next_state(Eigen::VectorXd::Zero(2));
  committed_ = trial_;
}

bool CombinationGap::is_nonlinear(const ElementContext&) const {
  return data_.gap != 0.0 || data_.fslide != 0.0;
}

bool CombinationGap::has_status() const {
  return data_.gap != 0.0 || data_.fslide != 0.0;
}

double CombinationGap::deflection(const Eigen::VectorXd& u) const {
  return u(1) - u(0) + data_.gap;
}

CombinationGap::State CombinationGap::closed_state(double delta) const {
  State s;
  s.status = GapStatus::Closed;
  s.slip = committed_.slip;
  s.direction = committed_.direction;
  s.broken = committed_.broken;
  if (s.broken) {
    s.status = GapStatus::Sliding;
    s.slip = delta;
    return s;
  }
  if (data_.fslide == 0.0 || data_.k1 == 0.0) return s;
  const double f1_trial = data_.k1 * (delta - committed_.slip);
  const double limit = std::abs(data_.fslide);
  if (std::abs(f1_trial) > limit) {
    s.status = GapStatus::Sliding;
    s.direction = f1_trial > 0.0 ? 1.0 : -1.0;
    if (data_.fslide < 0.0) {
      // Break-away: the K1 branch releases for good.
      s.broken = true;
      s.slip = delta;
    } else {
      s.slip = delta - s.direction * limit / data_.k1;
    }
  }
  return s;
}

CombinationGap::Forces CombinationGap::forces(const State& s, const Eigen::VectorXd& u) const {
  Forces f;
  f.delta = deflection(u);
  f.slip = s.slip;
  if (s.status == GapStatus::Open) return f;
  f.closed = true;
  f.s2 = data_.k2;
  f.f2 = data_.k2 * f.delta;
  if (s.status == GapStatus::Sliding) {
    if (!s.broken) {
      f.f1 = s.direction * std::abs(data_.fslide);
      f.slip = f.delta - f.f1 / data_.k1;
    } else {
      f.slip = f.delta;
    }
  } else {
    f.s1 = data_.k1;
    f.f1 = data_.k1 * (f.delta - s.slip);
  }
  return f;
}

CombinationGap::State CombinationGap::next_state(const Eigen::VectorXd& u) const {
  const double delta = deflection(u);
  const State candidate = closed_state(delta);
  if (!gap_capable()) return candidate;
  const Forces f = forces(candidate, u);
  const double force = f.f1 + f.f2;
  bool closed;
  if (trial_.status == GapStatus::Open) {
    closed = delta <= 0.0 && force <= 0.0;
  } else {
    closed = data_.lock_up || force <= 0.0;
  }
  if (closed) return candidate;
  State open = committed_;
  open.status = GapStatus::Open;
  return open;
}

void CombinationGap::tangent(const ElementContext&, const Eigen::VectorXd& u, Eigen::MatrixXd& K,
                             Eigen::VectorXd& f_int) const {
  const Forces f = forces(trial_, u);
  const double k = f.s1 + f.s2;
  K.resize(2, 2);
  K << k, -k, -k, k;
  const double force = f.f1 + f.f2;
  f_int.resize(2);
  f_int << -force, force;
}

void CombinationGap::mass(const ElementContext&, Eigen::MatrixXd& M) const {
  M.setZero(2, 2);
  switch (data_.mass_location) {
    case 0:
      M(0, 0) = data_.m;
      break;
    case 1:
      M(0, 0) = M(1, 1) = 0.5 * data_.m;
      break;
    default:
      M(1, 1) = data_.m;
      break;
  }
}

void CombinationGap::damping(const ElementContext&, const Eigen::VectorXd&,
                             Eigen::MatrixXd& C) const {
  const double c = trial_.status == GapStatus::Open ? 0.0 : data_.c;
  C.resize(2, 2);
  C << c, -c, -c, c;
}

bool CombinationGap::update_status(const ElementContext&, const Eigen::VectorXd& u) {
  if (frozen_ || !has_status()) return false;
  const State next = next_state(u);
  const bool changed = next.status != trial_.status;
  trial_ = next;
  return changed;
}

void CombinationGap::commit(const Eigen::VectorXd& u) {
  if (trial_.status == GapStatus::Sliding) trial_.slip = forces(trial_, u).slip;
  committed_ = trial_;
  frozen_ = false;
}

void CombinationGap::revert() {
  trial_ = committed_;
  frozen_ = false;
}

std::vector<double> CombinationGap::history_state() const {
  if (!has_status()) return {};
  const State& s = committed_;
  return {static_cast<double>(s.status), s.slip, s.direction, s.broken ? 1.0 : 0.0};
}

void CombinationGap::restore_history_state(const std::vector<double>& state) {
  IMPACTFE_CHECK(state.size() == (has_status() ? 4u : 0u),
                 "COMBIN40: saved state of the wrong length");
  if (state.empty()) return;
  committed_.status = static_cast<GapStatus>(static_cast<int>(state[0]));
  committed_.slip = state[1];
  committed_.direction = state[2];
  committed_.broken = state[3] != 0.0;
  trial_ = committed_;
  frozen_ = false;
}

namespace {
// SENE: the energy stored in the springs, F1²/(2 K1) + F2²/(2 K2) (the slider stores none).
const std::vector<std::string> kCombinationGapResults = {"FORC",  "F1",    "F2",  "STAT",
                                                         "DELTA", "SLIDE", "SENE"};
}  // namespace

const std::vector<std::string>& CombinationGap::result_names() const {
  return kCombinationGapResults;
}

void CombinationGap::results(const ElementContext&, const Eigen::VectorXd& u,
                             const Eigen::VectorXd&, ElementResultValues& out) const {
  const Forces f = forces(trial_, u);
  double energy = 0.0;
  if (data_.k1 > 0.0) energy += 0.5 * f.f1 * f.f1 / data_.k1;
  if (data_.k2 > 0.0) energy += 0.5 * f.f2 * f.f2 / data_.k2;
  out = {f.f1 + f.f2, f.f1,   f.f2,  static_cast<double>(static_cast<int>(trial_.status)),
         f.delta,     f.slip, energy};
}

namespace {

std::unique_ptr<Element> make_combination_gap(const ElementBuildContext& ctx,
                                              const ElementRecord& record) {
  const Model& model = ctx.model;
  constexpr const char* family = "CombinationGap";
  const ElementType& type = line_data::element_type(model, record);
  const auto [ni, nj] = line_data::distinct_node_pair(model, record, family);
  const int k3 = type.key(3);
  if (k3 < 0 || k3 > 6)
    throw InputError(record.where,
                     fmt::format("element {} ({}): KEYOPT(3) = {} is not supported (0..6: "
                                 "UX UX UY UZ ROTX ROTY ROTZ)",
                                 record.id, family, k3));
  const Dof dof = k3 == 0 ? Dof::UX : static_cast<Dof>(k3 - 1);
  const int k6 = type.key(6);
  if (k6 < 0 || k6 > 2)
    throw InputError(record.where,
                     fmt::format("element {} ({}): KEYOPT(6) = {} is not supported (0, 1, 2)",
                                 record.id, family, k6));
  const RealSet& real = line_data::real_set(model, record, family);
  CombinationGapData data;
  data.k1 = real.get(1);
  data.c = real.get(2);
  data.m = real.get(3);
  data.gap = real.get(4);
  data.fslide = real.get(5);
  data.k2 = real.get(6);
  data.lock_up = type.key(1) == 1;
  data.mass_location = k6;
  // Without springs the element is a damper C and a mass M (vm9 uses one, R,3,,1.41,1, which
  // MAPDL runs although its element notes ask for K1 or K2): linear, nothing to open or slide.
  // A gap or a slider would carry no force there, so they are refused.
  if (data.k1 == 0.0 && data.k2 == 0.0 && (data.gap != 0.0 || data.fslide != 0.0))
    throw InputError(record.where,
                     fmt::format("element {} ({}): K1 and K2 are both zero, so GAP = {:g} and "
                                 "FSLIDE = {:g} would carry no force; give K1 or K2, or leave "
                                 "GAP and FSLIDE zero for a pure damper and mass (real set {})",
                                 record.id, family, data.gap, data.fslide, record.real));
  if (data.k1 < 0.0 || data.k2 < 0.0 || data.c < 0.0 || data.m < 0.0)
    throw InputError(record.where,
                     fmt::format("element {} ({}): K1, C, M and K2 must not be negative (real "
                                 "set {})",
                                 record.id, family, record.real));
  return std::make_unique<CombinationGap>(record.id,
                                          std::vector<DofKey>{{ni.id, dof}, {nj.id, dof}}, data);
}

const ElementRegistration kCombin40{{.name = "COMBIN40",
                                     .number = 40,
                                     .family = "CombinationGap",
                                     .n_nodes = 2,
                                     .real_constants = RealConstantUse::Required,
                                     .vtk_cell = VtkCell::Line,
                                     .role = ShapeRole::Gap,
                                     .result_names = kCombinationGapResults,
                                     // STAT: MAPDL counts 1 open, 2 closed, 3 sliding.
                                     .result_sequences = {{"SMISC", "1", "FORC"},
                                                          {"NMISC", "2", "STAT", 1.0},
                                                          {"NMISC", "4", "SLIDE"}},
                                     .has_status = true,
                                     .create = make_combination_gap}};

}  // namespace

}  // namespace impactfe
