// CHOLMOD's static archive is built with OpenMP: its supernodal numeric factorization opens
// parallel regions to clear and copy blocks (GOMP_parallel, omp_get_num_threads,
// omp_get_thread_num). impactfe links no OpenMP runtime (issue 11): its element loops run on
// core/thread_pool.h, its BLAS is OpenBLAS on one thread, loaded with a passive wait policy by
// linalg/blas_library.cpp. These definitions run CHOLMOD's regions as teams of one thread on
// the calling thread — a valid OpenMP execution of them — so that no runtime starts (with its
// spinning default) just for CHOLMOD's bookkeeping. They are not exported: a library loaded
// later (OpenBLAS and its libgomp) binds to its own runtime.
extern "C" {

void GOMP_parallel(void (*body)(void*), void* data, unsigned /*num_threads*/, unsigned /*flags*/) {
  body(data);
}

int omp_get_num_threads() {
  return 1;
}

int omp_get_thread_num() {
  return 0;
}
}
