// Explicit dynamics: the cost of one central-difference cycle per SOLID164 element (element
// kernel, fixed-order nodal force sums, the nodal update) on n x n x n blocks of bricks, from
// 10^3 to 10^5 elements (docs/explicit_dynamics.md, "Speed"). The counter ns_per_element_cycle
// is the figure the run summary prints.
#include <benchmark/benchmark.h>

#include <cmath>

#include "core/model.h"
#include "explicit/central_difference.h"
#include "explicit/explicit_system.h"

namespace impactfe {
namespace {

/// A steel block of n³ unit-cube bricks (mm, N, t), built directly (no deck parsing).
Model block(int n) {
  Model m;
  m.element_types[1] = ElementType{.id = 1, .ansys_name = "SOLID164"};
  m.materials[1].id = 1;
  m.materials[1].props = {{"EX", 2.0e5}, {"NUXY", 0.3}, {"DENS", 7.8e-9}};
  const auto id = [n](int i, int j, int k) { return 1 + i + (n + 1) * (j + (n + 1) * k); };
  for (int k = 0; k <= n; ++k)
    for (int j = 0; j <= n; ++j)
      for (int i = 0; i <= n; ++i) {
        Node& node = m.nodes[id(i, j, k)];
        node.id = id(i, j, k);
        node.x = Vec3(i, j, k);
      }
  int e = 0;
  for (int k = 0; k < n; ++k)
    for (int j = 0; j < n; ++j)
      for (int i = 0; i < n; ++i) {
        ElementRecord& r = m.elements[++e];
        r.id = e;
        r.nodes = {
            id(i, j, k),     id(i + 1, j, k),     id(i + 1, j + 1, k),     id(i, j + 1, k),
            id(i, j, k + 1), id(i + 1, j, k + 1), id(i + 1, j + 1, k + 1), id(i, j + 1, k + 1)};
      }
  return m;
}

void BM_Solid164Cycle(benchmark::State& state) {
  const int n = static_cast<int>(state.range(0));
  Model m = block(n);
  ExplicitSystem s = build_explicit_system(m);
  CentralDifference cd(s, m.explicit_dynamics);
  // A compression with a twist: every element strains and spins.
  for (std::size_t i = 0; i < s.n_nodes(); ++i)
    cd.set_velocity(
        i, Vec3(-1e3 * (s.x0[i] / n - 0.5), 2e2 * (s.z0[i] / n - 0.5), -2e2 * (s.y0[i] / n - 0.5)));
  cd.set_loads(std::vector<std::uint8_t>(3 * s.n_nodes(), 0), Vec3::Zero());
  cd.start();
  for (auto _ : state) cd.cycle(cd.stable_step());
  const double elements = static_cast<double>(s.n_elements());
  state.counters["elements"] = elements;
  state.counters["ns_per_element_cycle"] =
      benchmark::Counter(elements * static_cast<double>(state.iterations()) * 1e-9,
                         benchmark::Counter::kIsRate | benchmark::Counter::kInvert);
}
BENCHMARK(BM_Solid164Cycle)->Arg(10)->Arg(22)->Arg(46)->Unit(benchmark::kMillisecond);

}  // namespace
}  // namespace impactfe

BENCHMARK_MAIN();
