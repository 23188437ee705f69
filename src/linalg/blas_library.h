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
/// - BLAS runs on one thread, whatever --threads says. OpenBLAS's threaded kernels (dgemm,
///   dtrsm, dsyrk, dpotrf) round differently by thread count: the 155 522-DOF dome's results
///   differed by up to 6.8e-8 of their peak between --threads 1 and 2, where issue 11 asks for
///   bitwise equal ones. Nor did the threads pay here: the dome's factorization took 1.11-1.61 s
///   with two against 0.93-1.01 s with one (docs/benchmarks.md, stop 33).
/// - OpenMP (the team OpenBLAS runs on) starts after OMP_WAIT_POLICY=passive is set, unless the
///   user set it, so that an OpenMP team another library starts does not spin.
#include <string>

namespace impactfe::blas {

/// Loads the libraries (once). Throws std::runtime_error naming them and the loader's reason
/// when they cannot be loaded; the factorization that needs them then reports it.
void require();
bool loaded();

/// Threads the loaded BLAS runs on (OpenBLAS's own count: 1); 0 when the library is not loaded
/// or does not say.
int threads();

/// "OpenBLAS 0.3.21 (libblas.so.3)", or "not loaded": for the run summary and benchmarks.
std::string describe();

}  // namespace impactfe::blas
