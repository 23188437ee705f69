// The explicit spar LINK160 and point mass MASS166 (MAPDL Element Reference release 18.2;
// docs/explicit_dynamics.md). LINK160: nodes I, J (K, the orientation node of MAPDL, is not
// needed by an axial bar and may be given), real constant AREA, axial force only; hypoelastic
// axial stress σ̇ = E ε̇ with ε̇ = e·(v_J − v_I)/L on the current axis e and length L, the radial
// return of TB plasticity in 1-D, lumped mass ρAL₀/2 at each end, stable step L/√(E/ρ).
// MASS166: node I, real constant MASS (KEYOPT(1) = 0, translational mass).
// Both run only in explicit analyses (their implicit factories refuse).
#include <fmt/format.h>

#include <algorithm>
#include <cmath>
#include <limits>
#include <map>

#include "elements/element_fields.h"
#include "elements/element_registry.h"
#include "materials/isotropic_elasticity.h"
#include "materials/rate_plasticity.h"

namespace impactfe {

namespace {

const std::string kLinkFamily = "Link160";
const std::string kMassFamily = "Mass166";
const std::vector<std::string> kLinkResults = {"SAXL", "FORC", "EPEQ"};
const std::vector<std::string> kMassResults = {};

const RealSet& real_set(const ExplicitBuildContext& ctx, const ElementRecord& r, const char* name) {
  const auto it = ctx.model.real_sets.find(r.real);
  if (it == ctx.model.real_sets.end())
    throw InputError(
        r.where, fmt::format("element {}: {} needs real constant set {} (R)", r.id, name, r.real));
  const ElementType& type = ctx.model.element_type(r.type);
  if (const std::string why = keyopt_refusal(type); !why.empty())
    throw InputError(type.where.known() ? type.where : r.where,
                     fmt::format("element type {}: {}", type.id, why));
  if (const std::string why = real_set_refusal(type, it->second); !why.empty())
    throw InputError(r.where, fmt::format("element {}: {}", r.id, why));
  return it->second;
}

class Link160Set final : public ExplicitElementSet {
 public:
  Link160Set(const ExplicitBuildContext& ctx, const std::vector<const ElementRecord*>& records);
  const std::string& family() const override { return kLinkFamily; }
  std::size_t size() const override { return ids_.size(); }
  int element_id(std::size_t k) const override { return ids_[k]; }
  int nodes_per_element() const override { return 2; }
  const int* nodes(std::size_t k) const override { return &nodes_[2 * k]; }
  void add_element_mass(std::size_t k, std::vector<double>& mass) const override {
    for (int a = 0; a < 2; ++a) mass[nodes_[2 * k + a]] += 0.5 * density_[k] * volume_[k];
  }
  /// ∫ρA x xᵀ ds, x linear along the link: m (x₁x₁ᵀ + x₂x₂ᵀ)/3 + m (x₁x₂ᵀ + x₂x₁ᵀ)/6.
  Eigen::Matrix3d second_mass_moment(const ExplicitNodalView& s, std::size_t k) const override {
    const int i = nodes_[2 * k], j = nodes_[2 * k + 1];
    const Eigen::Vector3d a(s.x[i], s.y[i], s.z[i]), b(s.x[j], s.y[j], s.z[j]);
    const double m = density_[k] * volume_[k];
    return m / 3.0 * (a * a.transpose() + b * b.transpose()) +
           m / 6.0 * (a * b.transpose() + b * a.transpose());
  }
  double element_step(const ExplicitNodalView& s, std::size_t k) const override {
    return length(s, k) / wave_speed(k);
  }
  double scale_mass(std::size_t k, double factor, std::vector<double>& mass) override {
    const double added = (factor - 1.0) * density_[k] * volume_[k];
    for (int a = 0; a < 2; ++a) mass[nodes_[2 * k + a]] += 0.5 * added;
    density_[k] *= factor;
    return added;
  }
  void results(Eigen::MatrixXd& out) const override {
    out.resize(static_cast<Eigen::Index>(size()), 3);
    for (std::size_t k = 0; k < size(); ++k) {
      const auto row = static_cast<Eigen::Index>(k);
      out(row, 0) = stress_[k];
      out(row, 1) = stress_[k] * area_[k];
      out(row, 2) = alpha_[k];
    }
  }

 private:
  double length(const ExplicitNodalView& s, std::size_t k) const {
    const int i = nodes_[2 * k], j = nodes_[2 * k + 1];
    return std::hypot(s.x[j] - s.x[i], s.y[j] - s.y[i], s.z[j] - s.z[i]);
  }
  double wave_speed(std::size_t k) const {
    return std::sqrt(materials_[static_cast<std::size_t>(material_[k])].young / density_[k]);
  }
  struct Material {
    double young = 0.0;
    std::optional<J2Plasticity> plasticity;
  };
  std::vector<int> ids_, nodes_, material_;
  std::vector<double> area_, volume_, density_, stress_, back_, alpha_;
  std::vector<Material> materials_;
  ExplicitStepLimit chunk_forces(const ExplicitNodalView& s, double dt, double* f, double*,
                                 std::size_t begin, std::size_t end,
                                 ExplicitSetEnergies& energies) override;
};

Link160Set::Link160Set(const ExplicitBuildContext& ctx,
                       const std::vector<const ElementRecord*>& records) {
  std::map<int, int> material_index;
  for (const ElementRecord* r : records) {
    if (r->nodes.size() < 2 || r->nodes[0] == r->nodes[1] || r->nodes[1] == 0)
      throw InputError(r->where,
                       fmt::format("element {}: LINK160 needs two distinct nodes I, J", r->id));
    const double area = real_set(ctx, *r, "LINK160").get(1);
    if (!(area > 0.0))
      throw InputError(r->where, fmt::format("element {}: LINK160 AREA (R1) must be > 0", r->id));
    const IsotropicElasticity e = read_isotropic_elasticity(ctx.model, r->mat, r->id, r->where);
    if (!(e.density > 0.0))
      throw InputError(r->where, fmt::format("element {}: material {} has no density (DENS): "
                                             "explicit dynamics needs the mass of every element",
                                             r->id, r->mat));
    auto [it, added] = material_index.emplace(r->mat, static_cast<int>(materials_.size()));
    if (added)
      materials_.push_back({e.young, plasticity_of(ctx.model, *r, e.young, e.poisson, false)});
    const Vec3 d = ctx.model.node(r->nodes[1]).x - ctx.model.node(r->nodes[0]).x;
    for (int a = 0; a < 2; ++a) nodes_.push_back(ctx.node_index(r->nodes[a], *r));
    ids_.push_back(r->id);
    material_.push_back(it->second);
    area_.push_back(area);
    volume_.push_back(area * d.norm());
    density_.push_back(e.density);
  }
  stress_.assign(ids_.size(), 0.0);
  back_.assign(ids_.size(), 0.0);
  alpha_.assign(ids_.size(), 0.0);
}

ExplicitStepLimit Link160Set::chunk_forces(const ExplicitNodalView& s, double dt, double* f,
                                           double*, std::size_t begin, std::size_t end,
                                           ExplicitSetEnergies& energies) {
  ExplicitStepLimit limit;
  for (std::size_t k = begin; k < end; ++k) {
    const int i = nodes_[2 * k], j = nodes_[2 * k + 1];
    const Vec3 axis(s.x[j] - s.x[i], s.y[j] - s.y[i], s.z[j] - s.z[i]);
    const double l = axis.norm();
    if (!(l > 0.0))
      throw ElementSolutionError(ids_[k],
                                 fmt::format("element {} (LINK160) has zero length", ids_[k]));
    const Vec3 e = axis / l;
    const double rate = e.dot(Vec3(s.vx[j] - s.vx[i], s.vy[j] - s.vy[i], s.vz[j] - s.vz[i])) / l;
    const Material& m = materials_[static_cast<std::size_t>(material_[k])];
    const double old = stress_[k];
    double trial = old + dt * m.young * rate;
    if (m.plasticity) {
      // 1-D radial return: |σ − β| − (k(α) + (H_kin + E)Δ) = 0, Δ ≥ 0 (the 1-D Box 3.1).
      const J2Plasticity& law = *m.plasticity;
      const double xi = trial - back_[k];
      const double over = std::abs(xi) - law.flow_stress(alpha_[k]);
      if (over > 0.0) {
        double delta = 0.0;
        for (int it = 0; it < 50; ++it) {
          const double r = std::abs(xi) - (m.young + law.kinematic_modulus()) * delta -
                           law.flow_stress(alpha_[k] + delta);
          const double step =
              r / (m.young + law.kinematic_modulus() + law.flow_slope(alpha_[k] + delta));
          delta = std::max(0.0, delta + step);
          if (std::abs(step) <= 1e-14 * (1.0 + delta)) break;
        }
        const double sign = xi > 0 ? 1.0 : -1.0;
        trial -= m.young * delta * sign;
        back_[k] += law.kinematic_modulus() * delta * sign;
        alpha_[k] += delta;
        energies.plastic_work += std::abs(trial) * delta * area_[k] * l;
      }
    }
    stress_[k] = trial;
    energies.internal += internal_work(k, dt * 0.5 * (old + trial) * rate * area_[k] * l);
    const double force = trial * area_[k];
    double* fk = f + 6 * k;
    for (int c = 0; c < 3; ++c) {
      fk[c] = -force * e(c);
      fk[3 + c] = force * e(c);
    }
    limit.take(l / wave_speed(k), ids_[k]);
  }
  return limit;
}

class Mass166Set final : public ExplicitElementSet {
 public:
  Mass166Set(const ExplicitBuildContext& ctx, const std::vector<const ElementRecord*>& records) {
    for (const ElementRecord* r : records) {
      const double mass = real_set(ctx, *r, "MASS166").get(1);
      if (!(mass > 0.0))
        throw InputError(r->where, fmt::format("element {}: MASS166 MASS (R1) must be > 0", r->id));
      ids_.push_back(r->id);
      nodes_.push_back(ctx.node_index(r->nodes.at(0), *r));
      mass_.push_back(mass);
    }
  }
  const std::string& family() const override { return kMassFamily; }
  std::size_t size() const override { return ids_.size(); }
  int element_id(std::size_t k) const override { return ids_[k]; }
  int nodes_per_element() const override { return 1; }
  const int* nodes(std::size_t k) const override { return &nodes_[k]; }
  void add_element_mass(std::size_t k, std::vector<double>& mass) const override {
    mass[nodes_[k]] += mass_[k];
  }
  Eigen::Matrix3d second_mass_moment(const ExplicitNodalView& s, std::size_t k) const override {
    const int n = nodes_[k];
    const Eigen::Vector3d x(s.x[n], s.y[n], s.z[n]);
    return mass_[k] * x * x.transpose();
  }
  // A point mass has no stiffness: no step limit, nothing to scale.
  double element_step(const ExplicitNodalView&, std::size_t) const override {
    return std::numeric_limits<double>::infinity();
  }
  double scale_mass(std::size_t, double, std::vector<double>&) override { return 0.0; }
  void results(Eigen::MatrixXd& out) const override {
    out.resize(static_cast<Eigen::Index>(size()), 0);
  }

 private:
  ExplicitStepLimit chunk_forces(const ExplicitNodalView&, double, double* f, double*,
                                 std::size_t begin, std::size_t end,
                                 ExplicitSetEnergies&) override {
    std::fill(f + 3 * begin, f + 3 * end, 0.0);
    return {};
  }
  std::vector<int> ids_, nodes_;
  std::vector<double> mass_;
};

const ElementRegistration kLink160{
    {.name = "LINK160",
     .number = 160,
     .family = kLinkFamily,
     .n_nodes = 2,
     .n_optional_nodes = 1,
     .real_constants = RealConstantUse::Required,
     .needs_material = true,
     .vtk_cell = VtkCell::Line,
     .role = ShapeRole::Line,
     .result_names = kLinkResults,
     .result_sequences = {{"LS", "1", "SAXL"}, {"SMISC", "1", "FORC"}, {"NL", "EPEQ", "EPEQ"}},
     .plasticity = true,
     .create = [](const ElementBuildContext&,
                  const ElementRecord& r) { return refuse_in_implicit_analysis(r, "LINK160"); },
     .explicit_set = [](const ExplicitBuildContext& ctx,
                        const std::vector<const ElementRecord*>& records)
         -> std::unique_ptr<ExplicitElementSet> {
       return std::make_unique<Link160Set>(ctx, records);
     }}};

const ElementRegistration kMass166{
    {.name = "MASS166",
     .number = 166,
     .family = kMassFamily,
     .n_nodes = 1,
     .real_constants = RealConstantUse::Required,
     .vtk_cell = VtkCell::Vertex,
     .role = ShapeRole::Point,
     .result_names = kMassResults,
     .create = [](const ElementBuildContext&,
                  const ElementRecord& r) { return refuse_in_implicit_analysis(r, "MASS166"); },
     .explicit_set = [](const ExplicitBuildContext& ctx,
                        const std::vector<const ElementRecord*>& records)
         -> std::unique_ptr<ExplicitElementSet> {
       return std::make_unique<Mass166Set>(ctx, records);
     }}};

}  // namespace

}  // namespace impactfe
