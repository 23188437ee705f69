#include "elements/beam_setup.h"

#include <fmt/format.h>

#include <Eigen/Dense>
#include <Eigen/Geometry>

#include <algorithm>
#include <cmath>
#include <stdexcept>

namespace impactfe {

InputError beam_element_error(const ElementRecord& record, const char* name,
                              const std::string& msg) {
  return InputError(record.where, fmt::format("element {} ({}): {}", record.id, name, msg));
}

Eigen::Matrix3d beam_frame(const ElementRecord& record, const char* name, const Vec3& xi,
                           const Vec3& xj, const Vec3* xk, double theta_deg) {
  constexpr double kPi = 3.14159265358979323846;
  const Vec3 ex = (xj - xi).normalized();
  Vec3 ey, ez;
  if (xk != nullptr) {
    const Vec3 v = *xk - xi;
    const Vec3 z = v - v.dot(ex) * ex;
    if (!(z.norm() > 1e-9 * std::max(v.norm(), (xj - xi).norm())))
      throw beam_element_error(record, name, "orientation node lies on the beam axis I-J");
    ez = z.normalized();
    ey = ez.cross(ex);
  } else {
    const Vec3 zg = Vec3::UnitZ();
    if (zg.cross(ex).norm() < 1e-6) {
      ey = Vec3::UnitY();
    } else {
      ey = zg.cross(ex).normalized();
    }
    ez = ex.cross(ey);
    const double t = theta_deg * kPi / 180.0;
    const Vec3 y0 = ey;
    ey = std::cos(t) * y0 + std::sin(t) * ez;
    ez = ex.cross(ey);
  }
  Eigen::Matrix3d R;
  R.col(0) = ex;
  R.col(1) = ey;
  R.col(2) = ez;
  return R;
}

BeamSectionProperties record_beam_section(const Model& model, const ElementRecord& record,
                                          const char* name, double nu, double shear_modulus) {
  const auto sec = model.sections.find(record.secnum);
  if (record.secnum <= 0 || sec == model.sections.end() || sec->second.type != "BEAM")
    throw beam_element_error(
        record, name,
        fmt::format("needs a beam section (SECTYPE,{},BEAM and SECNUM)", record.secnum));
  BeamSectionProperties p;
  try {
    p = beam_section_properties(sec->second.subtype, sec->second.data, nu);
  } catch (const std::invalid_argument& e) {
    throw beam_element_error(record, name, fmt::format("section {}: {}", record.secnum, e.what()));
  }
  // SECCONTROL: the transverse shear stiffnesses kGA given replace the computed ones (as shear
  // areas kGA/G of the element's material), and the added mass per length.
  const std::vector<double>& controls = sec->second.controls;
  const auto control = [&](std::size_t k) { return k < controls.size() ? controls[k] : 0.0; };
  if (control(0) > 0.0) p.shear_area_z = control(0) / shear_modulus;
  if (control(2) > 0.0) p.shear_area_y = control(2) / shear_modulus;
  if (control(0) > 0.0 || control(2) > 0.0) p.shear_note += ", SECCONTROL shear stiffness";
  p.added_mass = control(3);
  return p;
}

BeamFibreStresses beam_fibre_stresses(const BeamSectionProperties& p, double youngs_modulus,
                                      const Eigen::Matrix3d& D, double N, double My, double Mz) {
  const double E = youngs_modulus;
  const Eigen::Vector3d e = D.ldlt().solve(Eigen::Vector3d(N, My, Mz));
  BeamFibreStresses s;
  s.sdir = E * e(0);
  s.sbyt = -E * p.y_max * e(2);
  s.sbyb = -E * p.y_min * e(2);
  s.sbzt = E * p.z_max * e(1);
  s.sbzb = E * p.z_min * e(1);
  s.smax = s.sdir + std::max(s.sbyt, s.sbyb) + std::max(s.sbzt, s.sbzb);
  s.smin = s.sdir + std::min(s.sbyt, s.sbyb) + std::min(s.sbzt, s.sbzb);
  return s;
}

std::vector<ResultSequence> numbered_sequences(const char* item, int first,
                                               const std::vector<std::string>& names) {
  std::vector<ResultSequence> s;
  for (std::size_t k = 0; k < names.size(); ++k)
    if (!names[k].empty())
      s.push_back({item, std::to_string(first + static_cast<int>(k)), names[k]});
  return s;
}

}  // namespace impactfe
