#include "linalg/blas_library.h"

#include <dlfcn.h>
#include <fmt/format.h>

#include <atomic>
#include <cstdio>
#include <cstdlib>
#include <mutex>
#include <stdexcept>

namespace impactfe::blas {

namespace {

// The BLAS / LAPACK calling convention: every argument by address. The entry points below are
// declared with anonymous pointers and forward their arguments unchanged.
using P = void*;
using Fn5 = void (*)(P, P, P, P, P);
using Fn8 = void (*)(P, P, P, P, P, P, P, P);
using Fn10 = void (*)(P, P, P, P, P, P, P, P, P, P);
using Fn11 = void (*)(P, P, P, P, P, P, P, P, P, P, P);
using Fn13 = void (*)(P, P, P, P, P, P, P, P, P, P, P, P, P);

struct Library {
  void* blas = nullptr;
  void* lapack = nullptr;
  Fn13 dgemm = nullptr, zgemm = nullptr;
  Fn11 dgemv = nullptr, zgemv = nullptr, dtrsm = nullptr, ztrsm = nullptr;
  Fn10 dsyrk = nullptr, zherk = nullptr;
  Fn8 dtrsv = nullptr, ztrsv = nullptr;
  Fn5 dpotrf = nullptr, zpotrf = nullptr;
  void (*set_threads)(int) = nullptr;  // OpenBLAS only
  int (*get_threads)() = nullptr;      // OpenBLAS only
  char* (*config)() = nullptr;         // OpenBLAS only
  std::string name;
};

std::mutex load_mutex;
Library library;
std::atomic<bool> is_loaded{false};
std::string load_error;

constexpr const char* kBlasName = "libblas.so.3";
constexpr const char* kLapackName = "liblapack.so.3";

template <class F>
F symbol(void* handle, const char* name, std::string& missing) {
  void* p = dlsym(handle, name);
  if (!p) missing += (missing.empty() ? "" : ", ") + std::string(name);
  return reinterpret_cast<F>(p);
}

void load_locked() {
  if (is_loaded.load() || !load_error.empty()) return;
  // OpenMP reads its wait policy once, when the library starts: OpenBLAS's team then waits
  // passively between calls (the user's own setting wins).
  setenv("OMP_WAIT_POLICY", "PASSIVE", 0);
  Library lib;
  lib.blas = dlopen(kBlasName, RTLD_NOW | RTLD_LOCAL);
  if (!lib.blas) {
    load_error = fmt::format(
        "the BLAS library {} cannot be loaded ({}); install it with "
        "scripts/install-deps.sh (Debian: libopenblas0-openmp)",
        kBlasName, dlerror());
    return;
  }
  lib.lapack = dlopen(kLapackName, RTLD_NOW | RTLD_LOCAL);
  if (!lib.lapack) {
    load_error = fmt::format(
        "the LAPACK library {} cannot be loaded ({}); install it with "
        "scripts/install-deps.sh (Debian: libopenblas0-openmp)",
        kLapackName, dlerror());
    return;
  }
  std::string missing;
  lib.dgemm = symbol<Fn13>(lib.blas, "dgemm_", missing);
  lib.zgemm = symbol<Fn13>(lib.blas, "zgemm_", missing);
  lib.dgemv = symbol<Fn11>(lib.blas, "dgemv_", missing);
  lib.zgemv = symbol<Fn11>(lib.blas, "zgemv_", missing);
  lib.dtrsm = symbol<Fn11>(lib.blas, "dtrsm_", missing);
  lib.ztrsm = symbol<Fn11>(lib.blas, "ztrsm_", missing);
  lib.dsyrk = symbol<Fn10>(lib.blas, "dsyrk_", missing);
  lib.zherk = symbol<Fn10>(lib.blas, "zherk_", missing);
  lib.dtrsv = symbol<Fn8>(lib.blas, "dtrsv_", missing);
  lib.ztrsv = symbol<Fn8>(lib.blas, "ztrsv_", missing);
  lib.dpotrf = symbol<Fn5>(lib.lapack, "dpotrf_", missing);
  lib.zpotrf = symbol<Fn5>(lib.lapack, "zpotrf_", missing);
  if (!missing.empty()) {
    load_error = fmt::format("the BLAS / LAPACK libraries {} and {} lack {}", kBlasName,
                             kLapackName, missing);
    return;
  }
  lib.set_threads = reinterpret_cast<void (*)(int)>(dlsym(lib.blas, "openblas_set_num_threads"));
  lib.get_threads = reinterpret_cast<int (*)()>(dlsym(lib.blas, "openblas_get_num_threads"));
  lib.config = reinterpret_cast<char* (*)()>(dlsym(lib.blas, "openblas_get_config"));
  lib.name = lib.config ? fmt::format("OpenBLAS ({}): {}", kBlasName, lib.config())
                        : fmt::format("{} (not OpenBLAS)", kBlasName);
  library = lib;
  is_loaded.store(true);
  // One thread (blas_library.h): the same rounding whatever --threads says.
  if (library.set_threads) library.set_threads(1);
}

/// The library for an entry point: loaded on demand. The solvers call require() before the
/// factorizations that use BLAS, so a failure here means a caller that did not: an internal
/// error that cannot be thrown through CHOLMOD's C code.
const Library& get() {
  if (!is_loaded.load()) {
    const std::lock_guard<std::mutex> lock(load_mutex);
    load_locked();
    if (!is_loaded.load()) {
      std::fprintf(stderr, "internal error: BLAS called without the library: %s\n",
                   load_error.c_str());
      std::abort();
    }
  }
  return library;
}

}  // namespace

void require() {
  if (is_loaded.load()) return;
  const std::lock_guard<std::mutex> lock(load_mutex);
  load_locked();
  if (!is_loaded.load()) throw std::runtime_error(load_error);
}

bool loaded() {
  return is_loaded.load();
}

int threads() {
  return is_loaded.load() && library.get_threads ? library.get_threads() : 0;
}

std::string describe() {
  return is_loaded.load() ? library.name : std::string("not loaded");
}

}  // namespace impactfe::blas

// ---- the entry points CHOLMOD calls (its supernodal kernels) ----------------------------------
using impactfe::blas::P;
extern "C" {
void dgemm_(P a, P b, P c, P d, P e, P f, P g, P h, P i, P j, P k, P l, P m) {
  impactfe::blas::get().dgemm(a, b, c, d, e, f, g, h, i, j, k, l, m);
}
void zgemm_(P a, P b, P c, P d, P e, P f, P g, P h, P i, P j, P k, P l, P m) {
  impactfe::blas::get().zgemm(a, b, c, d, e, f, g, h, i, j, k, l, m);
}
void dgemv_(P a, P b, P c, P d, P e, P f, P g, P h, P i, P j, P k) {
  impactfe::blas::get().dgemv(a, b, c, d, e, f, g, h, i, j, k);
}
void zgemv_(P a, P b, P c, P d, P e, P f, P g, P h, P i, P j, P k) {
  impactfe::blas::get().zgemv(a, b, c, d, e, f, g, h, i, j, k);
}
void dtrsm_(P a, P b, P c, P d, P e, P f, P g, P h, P i, P j, P k) {
  impactfe::blas::get().dtrsm(a, b, c, d, e, f, g, h, i, j, k);
}
void ztrsm_(P a, P b, P c, P d, P e, P f, P g, P h, P i, P j, P k) {
  impactfe::blas::get().ztrsm(a, b, c, d, e, f, g, h, i, j, k);
}
void dsyrk_(P a, P b, P c, P d, P e, P f, P g, P h, P i, P j) {
  impactfe::blas::get().dsyrk(a, b, c, d, e, f, g, h, i, j);
}
void zherk_(P a, P b, P c, P d, P e, P f, P g, P h, P i, P j) {
  impactfe::blas::get().zherk(a, b, c, d, e, f, g, h, i, j);
}
void dtrsv_(P a, P b, P c, P d, P e, P f, P g, P h) {
  impactfe::blas::get().dtrsv(a, b, c, d, e, f, g, h);
}
void ztrsv_(P a, P b, P c, P d, P e, P f, P g, P h) {
  impactfe::blas::get().ztrsv(a, b, c, d, e, f, g, h);
}
void dpotrf_(P a, P b, P c, P d, P e) {
  impactfe::blas::get().dpotrf(a, b, c, d, e);
}
void zpotrf_(P a, P b, P c, P d, P e) {
  impactfe::blas::get().zpotrf(a, b, c, d, e);
}
}
