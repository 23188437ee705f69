#pragma once
/// The system BLAS and LAPACK (OpenBLAS from Debian: libblas.so.3 / liblapack.so.3), loaded when
/// a factorization first needs them (issue 11, start-up and threads).
///
/// CHOLMOD's supernodal kernels are the only BLAS/LAPACK callers in the program. The entry
/// points they name (dgemm_, dsyrk_, dtrsm_, dpotrf_, ... and the complex ones) are defined in
/// blas_library.cpp and forward to the library loaded here, so that
/// - a run that never makes a large supernodal factorization (the thesis decks, every small
///   model: SupernodalFactor or CHOLMOD's simplicial path) does not map OpenBLAS at all; its
///   ~12,000 symbol relocations were most of the dynamic loader's work at every start;
/// - OpenMP (the team OpenBLAS runs on) starts after OMP_WAIT_POLICY=passive is set, unless the
///   user set it: waiting threads sleep instead of spinning, which on a busy or virtual
///   two-core machine made two-thread factorizations 3.7 times slower than one-thread ones.
#include <string>

namespace impactfe::blas {

/// Loads the libraries (once). Throws std::runtime_error naming them and the loader's reason
/// when they cannot be loaded; the factorization that needs them then reports it.
void require();
bool loaded();

/// Threads of the BLAS calls that follow (OpenBLAS's own setting; applied when the library is
/// loaded later). n < 1 counts as 1.
void set_threads(int n);
int threads();

/// "OpenBLAS 0.3.21 (libblas.so.3)", or "not loaded": for the run summary and benchmarks.
std::string describe();

}  // namespace impactfe::blas
