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
           double density, double initial_strain, std::optional<J2Plasticity> plasticity)
    : Element(id),
      dofs_(std::move(dofs)),
      member_(std::move(member)),
      area_(area),
      youngs_modulus_(youngs_modulus),
      density_(density),
      initial_strain_(initial_strain),
      plasticity_(std::move(plasticity)) {}

AxialKinematics Spar::kinematics(const ElementContext& ctx) const {
  if (ctx.large_deflection) return AxialKinematics::Corotational;
  if (ctx.stress_stiffening) return AxialKinematics::StressStiffened;
  return AxialKinematics::Linear;
}

bool Spar::is_nonlinear(const ElementContext& ctx) const {
  return ctx.large_deflection || ctx.stress_stiffening || plasticity_.has_value();
}

corotational::AxialState Spar::respond(const ElementContext& ctx, const Eigen::VectorXd& u,
                                       Eigen::MatrixXd& K, Eigen::VectorXd& f,
                                       UniaxialPlasticState* updated) const {
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
  return out;
}

void Spar::restore_history_state(const std::vector<double>& state) {
  std::size_t pos = 0;
  if (plasticity_) read_state(state, pos, committed_);
  IMPACTFE_CHECK(pos == state.size(), "LINK: saved state of the wrong length");
}

void Spar::mass(const ElementContext& ctx, Eigen::MatrixXd& M) const {
  const int d = member_.dim();
  const double total = density_ * area_ * member_.length;
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
                                               "EPEQ", "SEPL", "SRAT", "PLWK"};
}  // namespace

const std::vector<std::string>& Spar::result_names() const {
  return kSparResults;
}

void Spar::results(const ElementContext& ctx, const Eigen::VectorXd& u, const Eigen::VectorXd&,
                   ElementResultValues& out) const {
  Eigen::MatrixXd K;
  Eigen::VectorXd f;
  UniaxialPlasticState state;  // the state at u (the committed one after a converged step)
  const auto s = respond(ctx, u, K, f, plasticity_ ? &state : nullptr);
  const double sigma = s.force / area_;
  out = {s.force, sigma, sigma / youngs_modulus_, s.current_length, 0.0, 0.0, 0.0, 0.0, 0.0};
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
                                   bool planar) {
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
  double area = 0.0;
  double initial_strain = 0.0;
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
    if (!area_from_section) area = real_it->second.get(1);
    initial_strain = real_it->second.get(2);
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
                                std::move(plasticity));
}

ElementTypeDescriptor spar_type(const char* name, int number, bool planar) {
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
                               {"NL", "EPEQ", "EPEQ"},
                               {"NL", "SEPL", "SEPL"},
                               {"NL", "SRAT", "SRAT"},
                               {"NL", "PLWK", "PLWK"}},
          .plasticity = true,
          .create = [planar](const ElementBuildContext& ctx, const ElementRecord& record) {
            return make_spar(ctx, record, planar);
          }};
}

const ElementRegistration kLink1{spar_type("LINK1", 1, true)};
const ElementRegistration kLink8{spar_type("LINK8", 8, false)};
const ElementRegistration kLink180{spar_type("LINK180", 180, false)};

}  // namespace

}  // namespace impactfe
