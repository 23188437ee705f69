// The explicit spring-damper COMBI165 (MAPDL Element Reference release 18.2;
// docs/explicit_dynamics.md, "COMBI165"): nodes I, J; its material is a TB,DISCRETE table,
// TBOPT 0 a linear elastic spring (C1 the stiffness k) or TBOPT 1 a linear viscous damper (C1
// the damping constant c), as LS-DYNA's *MAT_SPRING_ELASTIC and *MAT_DAMPER_VISCOUS. The force
// acts along the current axis e = (x_J − x_I)/L:
//   spring  N = k (L − L₀),   damper  N = c e·(v_J − v_I),
// with f_I = −N e, f_J = N e. The element has no mass (MASS166 or other elements give its nodes
// theirs). Its stable step is that of a two-mass oscillator, 2√(m/k) with m = m_I m_J/(m_I + m_J)
// (LS-DYNA Theory Manual, "Time step control", discrete elements; a node without mass, which
// must then be fixed, counts as immovable), and for the damper m/c, below which the lagged
// damper update v ← (1 − c Δt/m) v never reverses the relative velocity.
// It runs only in explicit analyses (its implicit factory refuses).
#include <fmt/format.h>

#include <cmath>
#include <limits>

#include "elements/element_fields.h"
#include "elements/element_registry.h"

namespace impactfe {

namespace {

const std::string kFamily = "Combi165";
const std::vector<std::string> kResults = {"FORC", "STRETCH"};

/// The k or c of an element's TB,DISCRETE material: TBOPT 0 spring, 1 damper.
struct Discrete {
  double stiffness = 0.0, damping = 0.0;
};

Discrete discrete_material(const Model& model, const ElementRecord& r) {
  const auto it = model.material_tables.find({r.mat, "DISCRETE"});
  if (it == model.material_tables.end())
    throw InputError(r.where, fmt::format("element {}: COMBI165 needs a TB,DISCRETE table for its "
                                          "material {} (TBOPT 0 spring, 1 damper)",
                                          r.id, r.mat));
  const MaterialTable& t = it->second;
  if (t.temperatures.size() != 1)
    throw InputError(t.where, "TB,DISCRETE: one temperature only (NTEMP = 1)");
  const std::vector<double>& c = t.temperatures.front().constants;
  const double value = c.empty() ? 0.0 : c.front();
  if (!(value > 0.0))
    throw InputError(t.where, fmt::format("TB,DISCRETE of material {}: C1 (the {} constant) must "
                                          "be > 0 (TBDATA,1,...)",
                                          r.mat, t.option == "1" ? "damping" : "spring"));
  for (std::size_t i = 1; i < c.size(); ++i)
    if (c[i] != 0.0)
      throw InputError(t.where, fmt::format("TB,DISCRETE of material {}: constant C{} = {:g} is "
                                            "not read (TBOPT {} takes C1 only)",
                                            r.mat, i + 1, c[i], t.option));
  return t.option == "1" ? Discrete{0.0, value} : Discrete{value, 0.0};
}

class Combi165Set final : public ExplicitElementSet {
 public:
  Combi165Set(const ExplicitBuildContext& ctx, const std::vector<const ElementRecord*>& records);
  const std::string& family() const override { return kFamily; }
  std::size_t size() const override { return ids_.size(); }
  int element_id(std::size_t k) const override { return ids_[k]; }
  int nodes_per_element() const override { return 2; }
  const int* nodes(std::size_t k) const override { return &nodes_[2 * k]; }
  void add_element_mass(std::size_t, std::vector<double>&) const override {}
  Eigen::Matrix3d second_mass_moment(const ExplicitNodalView&, std::size_t) const override {
    return Eigen::Matrix3d::Zero();
  }
  double element_step(const ExplicitNodalView& s, std::size_t k) const override {
    const double m = oscillator_mass(s, k);
    if (!(m > 0.0)) return std::numeric_limits<double>::infinity();  // both ends immovable
    return stiffness_[k] > 0.0 ? 2.0 * std::sqrt(m / stiffness_[k]) : m / damping_[k];
  }
  /// The step goes as √m (spring) or m (damper): the nodes get (factor − 1) times their mass so
  /// that the oscillator mass grows by `factor` (the factor the caller computed for √m; a
  /// damper's step then grows by the factor too, more than asked).
  double scale_mass(std::size_t k, double factor, std::vector<double>& mass) override {
    double added = 0.0;
    for (int a = 0; a < 2; ++a) {
      const double extra = (factor - 1.0) * mass[nodes_[2 * k + a]];
      mass[nodes_[2 * k + a]] += extra;
      added += extra;
    }
    return added;
  }
  void results(Eigen::MatrixXd& out) const override {
    out.resize(static_cast<Eigen::Index>(size()), 2);
    for (std::size_t k = 0; k < size(); ++k) {
      out(static_cast<Eigen::Index>(k), 0) = force_[k];
      out(static_cast<Eigen::Index>(k), 1) = length_[k] - rest_length_[k];
    }
  }

 private:
  /// m_I m_J/(m_I + m_J); a node without mass counts as immovable.
  double oscillator_mass(const ExplicitNodalView& s, std::size_t k) const {
    if (s.mass == nullptr) return 0.0;
    const double mi = s.mass[nodes_[2 * k]], mj = s.mass[nodes_[2 * k + 1]];
    if (mi > 0.0 && mj > 0.0) return mi * mj / (mi + mj);
    return mi + mj;
  }
  std::vector<int> ids_, nodes_;
  std::vector<double> stiffness_, damping_, rest_length_, length_, force_;
  ExplicitStepLimit chunk_forces(const ExplicitNodalView& s, double dt, double* f, double*,
                                 std::size_t begin, std::size_t end,
                                 ExplicitSetEnergies& energies) override;
};

Combi165Set::Combi165Set(const ExplicitBuildContext& ctx,
                         const std::vector<const ElementRecord*>& records) {
  for (const ElementRecord* r : records) {
    if (r->nodes.size() < 2 || r->nodes[0] == r->nodes[1] || r->nodes[1] == 0)
      throw InputError(r->where,
                       fmt::format("element {}: COMBI165 needs two distinct nodes I, J", r->id));
    const ElementType& type = ctx.model.element_type(r->type);
    if (const std::string why = keyopt_refusal(type); !why.empty())
      throw InputError(type.where.known() ? type.where : r->where,
                       fmt::format("element type {}: {}", type.id, why));
    if (const auto real = ctx.model.real_sets.find(r->real); real != ctx.model.real_sets.end())
      if (const std::string why = real_set_refusal(type, real->second); !why.empty())
        throw InputError(r->where, fmt::format("element {}: {}", r->id, why));
    const Vec3 d = ctx.model.node(r->nodes[1]).x - ctx.model.node(r->nodes[0]).x;
    // The force acts along the axis I-J: coincident nodes give it none.
    if (!(d.norm() > 0.0))
      throw InputError(r->where, fmt::format("element {}: COMBI165 nodes {} and {} coincide: the "
                                             "spring acts along I-J, which needs a length",
                                             r->id, r->nodes[0], r->nodes[1]));
    const Discrete m = discrete_material(ctx.model, *r);
    for (int a = 0; a < 2; ++a) nodes_.push_back(ctx.node_index(r->nodes[a], *r));
    ids_.push_back(r->id);
    stiffness_.push_back(m.stiffness);
    damping_.push_back(m.damping);
    rest_length_.push_back(d.norm());
  }
  length_ = rest_length_;
  force_.assign(ids_.size(), 0.0);
}

ExplicitStepLimit Combi165Set::chunk_forces(const ExplicitNodalView& s, double dt, double* f,
                                            double*, std::size_t begin, std::size_t end,
                                            ExplicitSetEnergies& energies) {
  ExplicitStepLimit limit;
  for (std::size_t k = begin; k < end; ++k) {
    const int i = nodes_[2 * k], j = nodes_[2 * k + 1];
    const Vec3 axis(s.x[j] - s.x[i], s.y[j] - s.y[i], s.z[j] - s.z[i]);
    const double l = axis.norm();
    if (!(l > 0.0))
      throw ElementSolutionError(
          ids_[k], fmt::format("element {} (COMBI165): its nodes met (zero length)", ids_[k]));
    const Vec3 e = axis / l;
    const double old = force_[k];
    double force = 0.0;
    if (stiffness_[k] > 0.0) {
      force = stiffness_[k] * (l - rest_length_[k]);
      // The work of a linear spring over the step, exact: ½(N_n + N_{n+1})(L_{n+1} − L_n).
      energies.internal += internal_work(k, 0.5 * (old + force) * (l - length_[k]));
    } else {
      const double rate = e.dot(Vec3(s.vx[j] - s.vx[i], s.vy[j] - s.vy[i], s.vz[j] - s.vz[i]));
      force = damping_[k] * rate;
      energies.internal += internal_work(k, dt * force * rate);  // dissipated: c ṡ² Δt
    }
    force_[k] = force;
    length_[k] = l;
    double* fk = f + 6 * k;
    for (int c = 0; c < 3; ++c) {
      fk[c] = -force * e(c);
      fk[3 + c] = force * e(c);
    }
    limit.take(element_step(s, k), ids_[k]);
  }
  return limit;
}

const ElementRegistration kCombi165{
    {.name = "COMBI165",
     .number = 165,
     .family = kFamily,
     .n_nodes = 2,
     .real_constants = RealConstantUse::Optional,
     .needs_material = true,
     .vtk_cell = VtkCell::Line,
     .role = ShapeRole::Line,
     .result_names = kResults,
     .result_sequences = {{"SMISC", "1", "FORC"}},
     .create =
         [](const ElementBuildContext&, const ElementRecord& r) {
           return refuse_in_implicit_analysis(r, "COMBI165", "; COMBIN14 is the implicit spring");
         },
     .explicit_set = [](const ExplicitBuildContext& ctx,
                        const std::vector<const ElementRecord*>& records)
         -> std::unique_ptr<ExplicitElementSet> {
       return std::make_unique<Combi165Set>(ctx, records);
     }}};

}  // namespace

}  // namespace impactfe
