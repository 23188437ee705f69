#pragma once
// The read kernel of the bandwidth measurements (bench_memory's BM_StreamRead, the floor of
// bench_kernels' BM_SupernodalSolve): the sum of n doubles with four partial sums, so that the
// loop is limited by the loads, not by the additions' latency.
#include <cstddef>

namespace impactfe::bench {

inline double stream_sum(const double* p, std::size_t n) {
  double s0 = 0.0, s1 = 0.0, s2 = 0.0, s3 = 0.0;
  for (std::size_t i = 0; i + 3 < n; i += 4) {
    s0 += p[i];
    s1 += p[i + 1];
    s2 += p[i + 2];
    s3 += p[i + 3];
  }
  return s0 + s1 + s2 + s3;
}

}  // namespace impactfe::bench
