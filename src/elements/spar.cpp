#include "elements/spar.h"

#include <fmt/format.h>

#include <cmath>

#include "elements/element_registry.h"
#include "elements/line_element_data.h"
#include "materials/linear_elastic.h"

namespace impactfe {

using corotational::AxialKinematics;
using corotational::AxialMember;

Spar::Spar(int id, std::vector<DofKey> dofs, AxialMember member, double area, double youngs_modulus,
           double density, double initial_strain, std::optional<J2Plasticity> plasticity,
           double added_mass, Carries carries)
    : Element(id),
      dofs_(std::move(dofs)),
      member_(std::move(member)),
      area_(area),
      youngs_modulus_(youngs_modulus),
      density_(density),
      initial_strain_(initial_strain),
      plasticity_(std::move(plasticity)),
      added_mass_(added_mass),
      carries_(carries) {}

AxialKinematics Spar::kinematics(const ElementContext& ctx) const {
  if (ctx.large_deflection) return AxialKinematics::Corotational;
  if (ctx.stress_stiffening) return AxialKinematics::StressStiffened;
  return AxialKinematics::Linear;
}

bool Spar::is_nonlinear(const ElementContext& ctx) const {
  // An initial strain makes the internal force affine, f = K u + f0, not the K u that the
  // assembler's linear products give (the static load and a transient's motion would miss f0).
  return ctx.large_deflection || ctx.stress_stiffening || plasticity_.has_value() ||
         initial_strain_ != 0.0 || carries_ != Carries::Both;
}

corotational::AxialState Spar::respond(const ElementContext& ctx, const Eigen::VectorXd& u,
                                       Eigen::MatrixXd& K, Eigen::VectorXd& f,
                                       UniaxialPlasticState* updated) const {
  if (slack_) {
    // A slack cable or gap carries nothing and adds no stiffness; its material does not move.
    const int n = 2 * member_.dim();
    K.setZero(n, n);
    f.setZero(n);
    if (updated != nullptr) *updated = committed_;
    corotational::AxialState none;
    none.current_length =
        (member_.length * member_.n + u.tail(member_.dim()) - u.head(member_.dim())).norm();
    return none;
  }
  const double ea = youngs_modulus_ * area_;
  const double length = member_.length;
  if (!plasticity_)
    return corotational::axial_response(member_, kinematics(ctx), ea / length, ea * initial_strain_,
                                        u, K, f, id());
  // Plastic: the axial response N = k e + N0 is linear in the extension e of the kinematics, so
  // the kinematics give e (k = 1, N0 = 0), the material gives σ(ε) and dσ/dε at ε = e/L + ISTRN,
  // and the member is evaluated again with the tangent k = A (dσ/dε) / L and N0 = Aσ − k e: the
  // same N and the consistent K_T (material + geometric part N/ℓ).
  const auto kin = corotational::axial_response(member_, kinematics(ctx), 1.0, 0.0, u, K, f, id());
  const UniaxialResponse m =
      plasticity_->uniaxial(committed_, kin.extension / length + initial_strain_, updated);
  const double k = area_ * m.tangent / length;
  return corotational::axial_response(member_, kinematics(ctx), k,
                                      area_ * m.stress - k * kin.extension, u, K, f, id());
}

void Spar::tangent(const ElementContext& ctx, const Eigen::VectorXd& u, Eigen::MatrixXd& K,
                   Eigen::VectorXd& f_int) const {
  respond(ctx, u, K, f_int, nullptr);
}

void Spar::commit_history(const ElementContext& ctx, const Eigen::VectorXd& u) {
  if (!plasticity_) return;
  Eigen::MatrixXd K;
  Eigen::VectorXd f;
  UniaxialPlasticState next;
  respond(ctx, u, K, f, &next);
  committed_ = next;
}

std::vector<double> Spar::history_state() const {
  std::vector<double> out;
  if (plasticity_) append_state(out, committed_);
  if (has_status()) out.push_back(committed_slack_ ? 1.0 : 0.0);
  return out;
}

void Spar::restore_history_state(const std::vector<double>& state) {
  std::size_t pos = 0;
  if (plasticity_) read_state(state, pos, committed_);
  if (has_status() && pos < state.size()) committed_slack_ = state[pos++] != 0.0;
  IMPACTFE_CHECK(pos == state.size(), "LINK: saved state of the wrong length");
  slack_ = committed_slack_;
  frozen_ = false;
}

bool Spar::update_status(const ElementContext& ctx, const Eigen::VectorXd& u) {
  if (frozen_ || carries_ == Carries::Both) return false;
  // The force the member would carry taut at u decides (LINK180, TENSKEY).
  const bool was = slack_;
  slack_ = false;
  Eigen::MatrixXd K;
  Eigen::VectorXd f;
  UniaxialPlasticState state;
  const double force = respond(ctx, u, K, f, plasticity_ ? &state : nullptr).force;
  slack_ = carries_ == Carries::TensionOnly ? force < 0.0 : force > 0.0;
  return slack_ != was;
}

void Spar::commit(const Eigen::VectorXd&) {
  committed_slack_ = slack_;
  frozen_ = false;
}

void Spar::revert() {
  slack_ = committed_slack_;
  frozen_ = false;
}

void Spar::mass(const ElementContext& ctx, Eigen::MatrixXd& M) const {
  const int d = member_.dim();
  const double total = (density_ * area_ + added_mass_) * member_.length;
  M.setZero(2 * d, 2 * d);
  if (ctx.lumped_mass) {
    M.diagonal().setConstant(0.5 * total);
    return;
  }
  const Eigen::MatrixXd I = Eigen::MatrixXd::Identity(d, d);
  M.topLeftCorner(d, d) = (total / 3.0) * I;
  M.bottomRightCorner(d, d) = (total / 3.0) * I;
  M.topRightCorner(d, d) = (total / 6.0) * I;
  M.bottomLeftCorner(d, d) = (total / 6.0) * I;
}

namespace {
const std::vector<std::string> kSparResults = {"FORC", "SAXL", "EPEL", "LENGTH", "EPPL",
                                               "EPEQ", "SEPL", "SRAT", "PLWK",   "EPTH"};
}  // namespace

const std::vector<std::string>& Spar::result_names() const {
  return kSparResults;
}

double Spar::thermal_axial_force() const {
  // The axial thermal strain ε_th = ALPX (T − T_ref) at the mean of the two end temperatures
  // (the temperature is linear along the bar and the strain constant).
  const std::vector<double>& dT = temperature_change();
  if (dT.size() < 2) return 0.0;
  return youngs_modulus_ * area_ * thermal_expansion().alpha.x() * 0.5 * (dT[0] + dT[1]);
}

void Spar::thermal_load(const ElementContext&, Eigen::VectorXd& f) const {
  // f = ∫ Bᵀ E ε_th A dx = E A ε_th (−n, n): the free bar's elongation ε_th L needs no force.
  const int d = member_.dim();
  const double n_th = thermal_axial_force();
  f.resize(2 * d);
  f.head(d) = -n_th * member_.n;
  f.tail(d) = n_th * member_.n;
}

void Spar::results(const ElementContext& ctx, const Eigen::VectorXd& u, const Eigen::VectorXd&,
                   ElementResultValues& out) const {
  Eigen::MatrixXd K;
  Eigen::VectorXd f;
  UniaxialPlasticState state;  // the state at u (the committed one after a converged step)
  const auto s = respond(ctx, u, K, f, plasticity_ ? &state : nullptr);
  // σ = E (ε − ε_th): the thermal strain's force E A ε_th is taken off the strain's force.
  const double force = s.force - thermal_axial_force();
  const double sigma = force / area_;
  // EPTH: the axial thermal strain ε_th (MAPDL LEPTH).
  const double epth = thermal_axial_force() / (youngs_modulus_ * area_);
  out = {force, sigma, sigma / youngs_modulus_, s.current_length, 0.0, 0.0, 0.0, 0.0, 0.0, epth};
  if (plasticity_) {
    const double flow = plasticity_->flow_stress(state.alpha);
    out[4] = state.plastic_strain;
    out[5] = state.alpha;
    out[6] = flow;
    out[7] = std::abs(sigma - state.back_stress) / flow;
    out[8] = state.plastic_work;
  }
}

namespace {

/// LINK1 (`planar`, UX UY in the X-Y plane) or LINK8 / LINK180 (UX UY UZ).
std::unique_ptr<Element> make_spar(const ElementBuildContext& ctx, const ElementRecord& record,
                                   bool planar, bool link180) {
  const Model& model = ctx.model;
  const char* family = planar ? "Spar 2-D" : "Spar";
  const auto [ni, nj] = line_data::distinct_node_pair(model, record, family);
  const Vec3 chord = nj.x - ni.x;
  const double length = chord.norm();
  if (!(length > 0.0))
    throw InputError(record.where,
                     fmt::format("element {} ({}): zero length (nodes {} and {} coincide)",
                                 record.id, family, ni.id, nj.id));
  if (planar && std::abs(chord.z()) > 1e-9 * length)
    throw InputError(record.where,
                     fmt::format("element {} ({}): LINK1 must lie in an X-Y plane (nodes {} and "
                                 "{} differ in Z by {})",
                                 record.id, family, ni.id, nj.id, chord.z()));

  // Area: LINK180 may take it from a LINK section (SECTYPE/SECDATA), otherwise real constant 1.
  // The other real constants differ by type (element_fields.cpp): LINK1 and LINK8 read R2 as
  // the initial strain ISTRN; LINK180 reads R2 as the added mass per unit length ADDMAS and R3
  // as TENSKEY (0 tension and compression, 1 tension only, -1 compression only).
  double area = 0.0;
  double initial_strain = 0.0;
  double added_mass = 0.0;
  Spar::Carries carries = Spar::Carries::Both;
  bool area_from_section = false;
  if (record.secnum > 0) {
    const auto sec = model.sections.find(record.secnum);
    if (sec != model.sections.end() && sec->second.type == "LINK" && !sec->second.data.empty()) {
      area = sec->second.data[0];
      area_from_section = true;
    }
  }
  const auto real_it = model.real_sets.find(record.real);
  if (real_it != model.real_sets.end()) {
    const RealSet& real = real_it->second;
    if (!area_from_section) area = real.get(1);
    if (link180) {
      added_mass = real.get(2);
      const double key = real.get(3);
      if (key != 0.0 && key != 1.0 && key != -1.0)
        throw InputError(record.where,
                         fmt::format("element {} (LINK180): TENSKEY (real constant 3) = {} must "
                                     "be 0 (tension and compression), 1 (tension only) or -1 "
                                     "(compression only)",
                                     record.id, key));
      carries = static_cast<Spar::Carries>(static_cast<int>(key));
      if (added_mass < 0.0)
        throw InputError(record.where,
                         fmt::format("element {} (LINK180): ADDMAS (real constant 2) = {} is "
                                     "negative",
                                     record.id, added_mass));
    } else {
      initial_strain = real.get(2);
    }
  } else if (!area_from_section) {
    throw InputError(record.where,
                     fmt::format("element {} ({}): real constant set {} (AREA) is not defined",
                                 record.id, family, record.real));
  }
  if (!(area > 0.0))
    throw InputError(record.where,
                     fmt::format("element {} ({}): AREA is missing or not positive (real set {})",
                                 record.id, family, record.real));
  const ElasticMaterial mat = elastic_material(model, record, family);
  auto plasticity = plasticity_of(model, record, mat.youngs_modulus, mat.poisson_ratio);

  const int d = planar ? 2 : 3;
  AxialMember member;
  member.n = (chord / length).head(d);
  member.length = length;
  std::vector<DofKey> dofs;
  for (int node : {ni.id, nj.id})
    for (int c = 0; c < d; ++c) dofs.push_back(DofKey{node, static_cast<Dof>(c)});
  return std::make_unique<Spar>(record.id, std::move(dofs), std::move(member), area,
                                mat.youngs_modulus, mat.density, initial_strain,
                                std::move(plasticity), added_mass, carries);
}

ElementTypeDescriptor spar_type(const char* name, int number, bool planar, bool link180 = false) {
  return {.name = name,
          .number = number,
          .family = "Spar",
          .n_nodes = 2,
          .real_constants = RealConstantUse::UnlessSection,
          .needs_material = true,
          .section_types = {"LINK"},
          .vtk_cell = VtkCell::Line,
          .role = ShapeRole::Line,
          .result_names = kSparResults,
          .result_sequences = {{"SMISC", "1", "FORC"},
                               {"LS", "1", "SAXL"},
                               {"LEPEL", "1", "EPEL"},
                               {"LEPPL", "1", "EPPL"},
                               {"LEPTH", "1", "EPTH"},
                               {"NL", "EPEQ", "EPEQ"},
                               {"NL", "SEPL", "SEPL"},
                               {"NL", "SRAT", "SRAT"},
                               {"NL", "PLWK", "PLWK"}},
          .plasticity = true,
          .create = [planar, link180](const ElementBuildContext& ctx, const ElementRecord& record) {
            return make_spar(ctx, record, planar, link180);
          }};
}

const ElementRegistration kLink1{spar_type("LINK1", 1, true)};
const ElementRegistration kLink8{spar_type("LINK8", 8, false)};
const ElementRegistration kLink180{spar_type("LINK180", 180, false, true)};

}  // namespace

}  // namespace impactfe
