// The threaded element loop of the explicit element sets (explicit_kernel.h).
#include "elements/explicit_kernel.h"

#include <fmt/format.h>

#include <algorithm>

#include "core/errors.h"
#include "core/thread_pool.h"
#include "elements/element.h"

namespace impactfe {

ExplicitStepLimit ExplicitElementSet::internal_forces_and_moments(const ExplicitNodalView& state,
                                                                  double dt, double* element_forces,
                                                                  double* element_moments) {
  const std::size_t n = size();
  if (element_energy_.size() != 2 * n) element_energy_.assign(2 * n, 0.0);
  if (has_rotations() && element_moments == nullptr) {
    // A run without rotations elsewhere still needs the set's moments computed (sized once).
    dropped_moments_.resize(3 * static_cast<std::size_t>(nodes_per_element()) * n);
    element_moments = dropped_moments_.data();
  }
  const std::size_t chunks = (n + kChunk - 1) / kChunk;
  if (chunks <= 1) {
    // One chunk: on this thread, without the pool's hand-over (a small model's cycle is a few
    // microseconds).
    ExplicitSetEnergies e;
    const ExplicitStepLimit limit =
        chunk_forces(state, dt, element_forces, element_moments, 0, n, e);
    energies_.internal += e.internal;
    energies_.hourglass += e.hourglass;
    energies_.plastic_work += e.plastic_work;
    return limit;
  }
  // Sized once: the per-chunk sums are cleared, not reallocated, each cycle.
  chunk_energies_.assign(chunks, ExplicitSetEnergies{});
  chunk_limits_.assign(chunks, ExplicitStepLimit{});
  threads::parallel_for(static_cast<int>(chunks), 1, [&](int c) {
    const std::size_t begin = static_cast<std::size_t>(c) * kChunk;
    chunk_limits_[static_cast<std::size_t>(c)] =
        chunk_forces(state, dt, element_forces, element_moments, begin, std::min(n, begin + kChunk),
                     chunk_energies_[static_cast<std::size_t>(c)]);
  });
  // In chunk order: the same sums and the same controlling element for any thread count.
  ExplicitStepLimit limit;
  for (std::size_t c = 0; c < chunks; ++c) {
    energies_.internal += chunk_energies_[c].internal;
    energies_.hourglass += chunk_energies_[c].hourglass;
    energies_.plastic_work += chunk_energies_[c].plastic_work;
    limit.take(chunk_limits_[c].dt, chunk_limits_[c].element);
  }
  return limit;
}

std::unique_ptr<Element> refuse_in_implicit_analysis(const ElementRecord& record, const char* name,
                                                     const char* alternative) {
  throw InputError(record.where,
                   fmt::format("element {}: {} is an explicit dynamics element: it runs in a "
                               "transient analysis whose elements are all explicit (16x) ones "
                               "(docs/explicit_dynamics.md){}",
                               record.id, name, alternative));
}

}  // namespace impactfe
