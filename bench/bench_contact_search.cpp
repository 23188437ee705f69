// Contact search micro-benchmark (issue 16, "the cost of contact search"): the rigid-target bucket
// grid of TARGE170 (elements/target_surface.h) built over a meshed floor and queried by the bottom
// nodes of a block resting on it, as CONTA175 does before every status update. Sizes: 10^3, 10^4,
// 10^5 contact nodes on an m x m grid (m = 32, 100, 317) of unit spacing; the floor has as many
// quads as the block's bottom face (2 triangles each) or is one quad (the plane of the drop
// tests). The pinball is 2 element depths (CONTA175's default PINB), the nodes 0.01 above the
// floor. Reported per query and per sweep of all nodes (one status update of every contact
// element). bench/run_contact_search.py puts these beside the step time of a whole run.
#include <benchmark/benchmark.h>

#include <cmath>
#include <vector>

#include "elements/target_surface.h"

namespace impactfe {
namespace {

using Triangle = TargetSurface::Triangle;

/// Floor z = 0 from -1 to m (unit cells, two triangles per cell), normal +Z; cells = 1 gives one
/// quad over the whole area.
std::vector<Triangle> floor_triangles(int m, int cells) {
  std::vector<Triangle> out;
  const double lo = -1.0, size = (m + 1.0) / cells;
  const Vec3 up(0.0, 0.0, 1.0);
  for (int j = 0; j < cells; ++j)
    for (int i = 0; i < cells; ++i) {
      const Vec3 a(lo + i * size, lo + j * size, 0.0), b(a.x() + size, a.y(), 0.0),
          c(a.x() + size, a.y() + size, 0.0), d(a.x(), a.y() + size, 0.0);
      out.push_back({a, b, c, up});
      out.push_back({a, c, d, up});
    }
  return out;
}

std::vector<Vec3> contact_nodes(int m) {
  std::vector<Vec3> out;
  out.reserve(static_cast<std::size_t>(m) * m);
  for (int j = 0; j < m; ++j)
    for (int i = 0; i < m; ++i) out.emplace_back(i + 0.37, j + 0.61, 0.01);
  return out;
}

constexpr double kReach = 2.0;  // PINB default: 2 x the element depth (1 here)

void BM_TargetBuild(benchmark::State& state) {
  const int m = static_cast<int>(state.range(0));
  const auto triangles = floor_triangles(m, m + 1);
  for (auto _ : state) {
    TargetSurface target(1, triangles);
    benchmark::DoNotOptimize(target);
  }
  state.counters["facets"] = static_cast<double>(triangles.size());
}

void search_sweep(benchmark::State& state, int cells_of_floor) {
  const int m = static_cast<int>(state.range(0));
  const TargetSurface target(1, floor_triangles(m, cells_of_floor < 0 ? m + 1 : cells_of_floor));
  const auto nodes = contact_nodes(m);
  std::size_t found = 0;
  for (auto _ : state) {
    found = 0;
    for (const Vec3& y : nodes) {
      const auto hit = target.closest(y, kReach);
      found += hit.has_value();
      benchmark::DoNotOptimize(hit);
    }
  }
  if (found != nodes.size()) state.SkipWithError("a contact node found no facet");
  state.counters["nodes"] = static_cast<double>(nodes.size());
  state.counters["per_query"] = benchmark::Counter(
      static_cast<double>(nodes.size()),
      benchmark::Counter::kIsIterationInvariantRate | benchmark::Counter::kInvert);
}

void BM_SearchMeshedFloor(benchmark::State& state) {
  search_sweep(state, -1);
}
void BM_SearchOneFacetFloor(benchmark::State& state) {
  search_sweep(state, 1);
}

BENCHMARK(BM_TargetBuild)->Arg(8)->Arg(32)->Arg(100)->Arg(317)->Unit(benchmark::kMillisecond);
BENCHMARK(BM_SearchMeshedFloor)->Arg(8)->Arg(32)->Arg(100)->Arg(317)->Unit(benchmark::kMillisecond);
BENCHMARK(BM_SearchOneFacetFloor)
    ->Arg(8)
    ->Arg(32)
    ->Arg(100)
    ->Arg(317)
    ->Unit(benchmark::kMillisecond);

}  // namespace
}  // namespace impactfe

BENCHMARK_MAIN();
