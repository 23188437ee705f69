#pragma once
/// What a time integrator needs to continue from a saved point (restart files, docs/
/// solution_control.md): u, v, a and, for multi-step schemes, the past displacements (Houbolt:
/// u_{n-1}, u_{n-2}). The integrators implement it beside TimeIntegrator; a driver reaches it
/// with dynamic_cast (kept out of time_integrator.h, which much of the program includes).
#include <Eigen/Core>

#include <vector>

namespace impactfe {

class IntegratorHistory {
 public:
  virtual ~IntegratorHistory() = default;
  virtual std::vector<Eigen::VectorXd> history() const = 0;
  /// Continues exactly as the integrator that gave `history`, with step h.
  virtual void restore(const std::vector<Eigen::VectorXd>& history, double h) = 0;
};

}  // namespace impactfe
