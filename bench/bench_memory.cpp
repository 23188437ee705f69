// Memory bandwidth of one thread, for the bandwidth floor of the benchmark suite
// (bench/run_benchmarks.py): a triangular solve streams the factor L twice (forward and backward
// substitution) and does about 2 flops per value read, so it cannot be faster than
// 2 * bytes(L) / bandwidth. CHOLMOD's solve runs on one thread, hence one-thread kernels.
//
// BM_StreamTriad: a[i] = b[i] + s * c[i], McCalpin's STREAM triad; bytes counted as in STREAM,
//   3 * 8 per element (the write-allocate read of a is not counted).
// BM_StreamRead: sum of a[i], read-only (closest to what a solve does with L).
//
// Usage: bench_memory [--length=N] [Google Benchmark flags]. N doubles per array, default 2^24
// (128 MiB per array), far beyond the caches of the machines this runs on; the arrays are
// allocated and touched once, outside the timed loops.
#include <benchmark/benchmark.h>

#include <cstddef>
#include <cstdlib>
#include <cstring>
#include <iostream>
#include <vector>

#include "stream_sum.h"

namespace {

struct Arrays {
  std::vector<double> a, b, c;
  explicit Arrays(std::size_t n) : a(n, 0.0), b(n, 1.0), c(n, 2.0) {}
};

void stream_triad(benchmark::State& state, Arrays* arrays) {
  const std::size_t n = arrays->a.size();
  const double s = 3.0;
  double* __restrict pa = arrays->a.data();
  const double* __restrict pb = arrays->b.data();
  const double* __restrict pc = arrays->c.data();
  for (auto _ : state) {
    for (std::size_t i = 0; i < n; ++i) pa[i] = pb[i] + s * pc[i];
    benchmark::DoNotOptimize(pa);
    benchmark::ClobberMemory();
  }
  state.SetBytesProcessed(static_cast<int64_t>(state.iterations()) *
                          static_cast<int64_t>(3 * sizeof(double) * n));
}

void stream_read(benchmark::State& state, Arrays* arrays) {
  const std::size_t n = arrays->b.size();
  const double* p = arrays->b.data();
  for (auto _ : state) {
    double sum = impactfe::bench::stream_sum(p, n);
    benchmark::DoNotOptimize(sum);
  }
  state.SetBytesProcessed(static_cast<int64_t>(state.iterations()) *
                          static_cast<int64_t>(sizeof(double) * n));
}

}  // namespace

int main(int argc, char** argv) {
  benchmark::Initialize(&argc, argv);
  std::size_t length = std::size_t{1} << 24;
  for (int i = 1; i < argc; ++i) {
    if (std::strncmp(argv[i], "--length=", 9) == 0) {
      length = std::strtoull(argv[i] + 9, nullptr, 10);
    } else {
      std::cerr << "bench_memory: unknown argument " << argv[i] << "\n";
      return 1;
    }
  }
  if (length < 1024) {
    std::cerr << "bench_memory: --length must be at least 1024\n";
    return 1;
  }
  Arrays arrays(length);
  benchmark::RegisterBenchmark("BM_StreamTriad", stream_triad, &arrays)
      ->Unit(benchmark::kMillisecond);
  benchmark::RegisterBenchmark("BM_StreamRead", stream_read, &arrays)
      ->Unit(benchmark::kMillisecond);
  benchmark::RunSpecifiedBenchmarks();
  benchmark::Shutdown();
  return 0;
}
