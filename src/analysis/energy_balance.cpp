#include "analysis/energy_balance.h"

#include <fmt/format.h>

#include <algorithm>
#include <cmath>

namespace impactfe {

EnergyBalance::EnergyBalance(const std::vector<std::unique_ptr<Element>>& elements)
    : elements_(elements) {
  for (std::size_t e = 0; e < elements_.size(); ++e) {
    if (elements_[e]->has_status()) status_elements_.push_back(e);
    if (elements_[e]->has_history()) history_elements_.push_back(e);
  }
  status_force_old_.resize(status_elements_.size());
}

void EnergyBalance::add_step(const Assembler& assembler, const VectorXd& u_old,
                             const VectorXd& u_new, const StepForces& f) {
  du_ = u_new - u_old;  // kept: no allocation per step (issue 11)
  const VectorXd& du = du_;
  external_work_ += 0.5 * (f.external_new + f.external_old).dot(du);
  damping_work_ += 0.5 * (f.damping_new + f.damping_old).dot(du);
  // Work on the status elements, element by element (trapezoidal rule on each).
  VectorXd ue_old, ue_new, f_now;
  Eigen::MatrixXd k;
  for (std::size_t s = 0; s < status_elements_.size(); ++s) {
    const std::size_t e = status_elements_[s];
    assembler.gather(e, u_old, ue_old);
    assembler.gather(e, u_new, ue_new);
    elements_[e]->tangent(assembler.context(), ue_new, k, f_now);
    VectorXd& f_old = status_force_old_[s];
    if (f_old.size() != f_now.size()) f_old = VectorXd::Zero(f_now.size());
    gap_work_ += 0.5 * (f_old + f_now).dot(ue_new - ue_old);
    f_old = f_now;
  }
  internal_work_ += 0.5 * (f.internal_new + f.internal_old).dot(du);
  peak_input_ = std::max(peak_input_, initial_kinetic_ + initial_strain_ + external_work_);
}

void EnergyBalance::start(const Assembler& assembler, const VectorXd& u0) {
  VectorXd ue;
  Eigen::MatrixXd k;
  for (std::size_t s = 0; s < status_elements_.size(); ++s) {
    assembler.gather(status_elements_[s], u0, ue);
    elements_[status_elements_[s]]->tangent(assembler.context(), ue, k, status_force_old_[s]);
  }
}

double EnergyBalance::plastic_work() const {
  double sum = 0.0;
  for (std::size_t e : history_elements_) sum += elements_[e]->plastic_work();
  return sum;
}

std::map<std::string, double> EnergyBalance::columns(double kinetic) const {
  std::map<std::string, double> out = {{"kinetic", kinetic},
                                       {"strain", strain_energy()},
                                       {"external_work", external_work_},
                                       {"gap_work", gap_work_},
                                       {"dissipation", damping_work_}};
  if (!history_elements_.empty()) out["plastic_work"] = plastic_work();
  return out;
}

double EnergyBalance::numerical_dissipation(double kinetic) const {
  // strain_energy() already excludes the plastic work: strain + plastic = internal − gap.
  return initial_kinetic_ + external_work_ - kinetic - strain_energy() - plastic_work() -
         gap_work_ - damping_work_;
}

std::optional<EnergyBalance::Creation> EnergyBalance::creation(double kinetic) const {
  const double reference =
      std::max(peak_input_, initial_kinetic_ + initial_strain_ + external_work_);
  if (!(reference > 0.0)) return std::nullopt;
  const double bound = kCreationBound * reference;
  // Gaps and contacts store energy while closed and dissipate it by friction: a negative work
  // on them is energy they created.
  // The strain energy of the IC displacements may be stored in them (a stretched slider's K2
  // spring): what they give back of it is not created.
  if (-gap_work_ - initial_strain_ > bound)
    return Creation{"gap/contact work", -gap_work_ - initial_strain_, reference,
                    "the gap/contact elements gave back more energy than they took: contact "
                    "closing and opening inside time steps that do not resolve it (chatter) or "
                    "a contact force kept across an open gap. Use a time step that resolves the "
                    "contact period (the time-step advice in the log), a softer contact "
                    "stiffness (FKN), or the penalty method (KEYOPT(2) = 1)"};
  // The remainder of the balance negative: kinetic + strain energy beyond what was put in.
  const double created = -numerical_dissipation(kinetic);
  if (created > bound)
    return Creation{"kinetic + strain energy", created, reference,
                    "the time integration created energy: an unstable step (a time step above "
                    "the stability limit of the integrator or of a stiff contact, Newmark "
                    "parameters outside DELTA >= 0.5, ALPHA >= (0.5 + DELTA)^2 / 4). Use a "
                    "smaller time step (DELTIM/DTIME), numerical damping (TINTP,0.005 or more) "
                    "or HHT (TRNOPT,,,,,,HHT)"};
  return std::nullopt;
}

std::optional<std::string> EnergyBalance::balance_warning(double kinetic) const {
  const double input = initial_kinetic_ + external_work_;
  if (!(input > 0.0)) return std::nullopt;
  // Gaps and contacts store energy while closed and dissipate it by friction: their work is
  // never negative, except through status changes inside steps that do not resolve them. The
  // remainder is the integrator's only when they did not create energy: this comes first.
  if (gap_work_ < -0.01 * input)
    return fmt::format(
        "the gap/contact elements gave back {:.4g} more energy than they took ({:.1f} % of the "
        "{:.4g} put in): contact created energy by closing and opening inside time steps that "
        "do not resolve it (chatter). Use a time step that resolves the contact period (the "
        "time-step advice above), a softer contact stiffness, and for impacts the penalty "
        "method (CONTA KEYOPT(2) = 1)",
        -gap_work_, -100.0 * gap_work_ / input, input);
  const double lost = numerical_dissipation(kinetic) / input;
  if (lost > 0.05)
    return fmt::format(
        "the time integration dissipated {:.1f} % of the energy put in ({:.4g} of {:.4g}): "
        "results are damped numerically. Use a smaller time step (DELTIM/DTIME or more "
        "substeps) or a less dissipative integrator (TRNOPT,FULL,,,,,NMK: Newmark, trapezoidal "
        "rule by default)",
        100.0 * lost, numerical_dissipation(kinetic), input);
  if (lost < -0.01)
    return fmt::format(
        "the energy balance is off by {:.1f} % of the energy put in (energy created: {:.4g} of "
        "{:.4g}): use a smaller time step (DELTIM/DTIME or more substeps)",
        -100.0 * lost, -numerical_dissipation(kinetic), input);
  return std::nullopt;
}

std::string EnergyBalance::summary(double time, double kinetic) const {
  // Dissipation and creation named as what they are: a negative gap work is energy the
  // gap/contact elements created, a negative remainder energy the integration created.
  const double remainder = numerical_dissipation(kinetic);
  return fmt::format(
      "energy at t = {:.6g}: kinetic {:.6g}, strain {:.6g}, gap work {:.6g}{}, damping {:.6g}, "
      "{}external work {:.6g}{}, {} {:.6g}",
      time, kinetic, strain_energy(), gap_work_,
      gap_work_ < 0.0 ? fmt::format(" (energy created by gaps/contact {:.6g})", -gap_work_) : "",
      damping_work_,
      history_elements_.empty() ? std::string()
                                : fmt::format("plastic work {:.6g}, ", plastic_work()),
      external_work_,
      initial_kinetic_ != 0.0 ? fmt::format(", initial kinetic {:.6g}", initial_kinetic_) : "",
      remainder >= 0.0 ? "numerical dissipation" : "energy created by the integration",
      std::abs(remainder));
}

std::vector<double> EnergyBalance::state() const {
  std::vector<double> s{initial_kinetic_, external_work_,
                        internal_work_,   gap_work_,
                        damping_work_,    static_cast<double>(status_force_old_.size())};
  for (const VectorXd& f : status_force_old_) {
    s.push_back(static_cast<double>(f.size()));
    s.insert(s.end(), f.data(), f.data() + f.size());
  }
  return s;
}

void EnergyBalance::restore(const std::vector<double>& s) {
  IMPACTFE_CHECK(s.size() >= 6, "EnergyBalance::restore: state too short");
  initial_kinetic_ = s[0];
  external_work_ = s[1];
  internal_work_ = s[2];
  gap_work_ = s[3];
  damping_work_ = s[4];
  peak_input_ = std::max(initial_kinetic_, initial_kinetic_ + external_work_);
  status_force_old_.assign(static_cast<std::size_t>(s[5]), VectorXd());
  std::size_t i = 6;
  for (VectorXd& f : status_force_old_) {
    IMPACTFE_CHECK(i < s.size(), "EnergyBalance::restore: state too short");
    const auto n = static_cast<Eigen::Index>(s[i++]);
    IMPACTFE_CHECK(i + static_cast<std::size_t>(n) <= s.size(),
                   "EnergyBalance::restore: state too short");
    f = Eigen::Map<const VectorXd>(s.data() + i, n);
    i += static_cast<std::size_t>(n);
  }
}

}  // namespace impactfe
