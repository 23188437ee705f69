#pragma once
/// Two doubles in one register (SSE2 on x86-64, NEON elsewhere), for the reductions the
/// compiler does not vectorize without reassociating: the dot products of the supernodal back
/// substitution and the transposed products over a row group's pairs of rows.
#include <cstring>

namespace impactfe::simd {

typedef double Pair __attribute__((vector_size(16)));

/// The two doubles at p (no alignment needed).
inline Pair load_pair(const double* p) {
  Pair v;
  std::memcpy(&v, p, sizeof v);
  return v;
}

}  // namespace impactfe::simd
