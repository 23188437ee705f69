// Energies by part (part_energies.h).
#include "explicit/part_energies.h"

#include <tuple>

namespace impactfe {

std::map<int, int> explicit_part_numbers(const Model& model) {
  std::map<std::tuple<int, int, int>, int> parts;
  for (const auto& [id, e] : model.elements) parts[{e.type, e.mat, e.real}] = 0;
  int number = 0;
  for (auto& [key, n] : parts) n = ++number;
  std::map<int, int> out;
  for (const auto& [id, e] : model.elements) out[id] = parts[{e.type, e.mat, e.real}];
  return out;
}

ExplicitPartEnergies::ExplicitPartEnergies(const Model& model, const ExplicitSystem& system) {
  const std::map<int, int> part = explicit_part_numbers(model);
  for (const auto& [id, p] : part) n_parts_ = std::max(n_parts_, static_cast<std::size_t>(p));
  // Each element's lumped mass by part at each of its nodes (rigid elements too).
  const std::size_t n = system.n_nodes();
  std::vector<std::map<int, double>> at_node(n);
  std::vector<double> scratch(n, 0.0);
  const auto collect = [&](const ExplicitElementSet& set, std::vector<int>* parts) {
    for (std::size_t k = 0; k < set.size(); ++k) {
      const int p = part.at(set.element_id(k)) - 1;
      if (parts) parts->push_back(p);
      set.add_element_mass(k, scratch);
      const int* nodes = set.nodes(k);
      for (int a = 0; a < set.nodes_per_element(); ++a) {
        const auto node = static_cast<std::size_t>(nodes[a]);
        if (scratch[node] != 0.0) at_node[node][p] += scratch[node];
        scratch[node] = 0.0;
      }
    }
  };
  for (const auto& set : system.sets) {
    part_of_.emplace_back();
    collect(*set, &part_of_.back());
  }
  for (const auto& set : system.rigid_sets) collect(*set, nullptr);
  share_start_.push_back(0);
  for (const auto& shares : at_node) {
    double total = 0.0;
    for (const auto& [p, m] : shares) total += m;
    for (const auto& [p, m] : shares) {
      share_part_.push_back(p);
      share_fraction_.push_back(m / total);
    }
    share_start_.push_back(share_part_.size());
  }
}

Eigen::VectorXd ExplicitPartEnergies::at(const ExplicitSystem& system,
                                         const CentralDifference& cd) const {
  Eigen::VectorXd e = Eigen::VectorXd::Zero(3 * static_cast<Eigen::Index>(n_parts_));
  for (std::size_t node = 0; node < system.n_nodes(); ++node) {
    double kinetic = 0.5 * system.mass[node] * cd.velocity(node).squaredNorm();
    if (cd.has_rotations(node))
      kinetic += 0.5 * system.inertia[node] * cd.angular_velocity(node).squaredNorm();
    for (std::size_t j = share_start_[node]; j < share_start_[node + 1]; ++j)
      e(3 * share_part_[j]) += share_fraction_[j] * kinetic;
  }
  for (std::size_t s = 0; s < system.sets.size(); ++s) {
    const std::vector<double>& w = system.sets[s]->element_energies();
    if (w.empty()) continue;  // before the first cycle
    for (std::size_t k = 0; k < part_of_[s].size(); ++k) {
      e(3 * part_of_[s][k] + 1) += w[2 * k];
      e(3 * part_of_[s][k] + 2) += w[2 * k + 1];
    }
  }
  return e;
}

}  // namespace impactfe
