#include "linalg/parallel_backend.h"

#include <dlfcn.h>
#include <fmt/format.h>

#include <cstdlib>
#include <exception>
#include <filesystem>
#include <memory>
#include <new>
#include <stdexcept>
#include <string>
#include <vector>

#include "core/files.h"
#include "linalg/linear_solver.h"
#include "linalg/mumps/mumps_module_api.h"

namespace impactfe {

namespace {

/// The module's entry points (linalg/mumps/mumps_module_api.h).
struct Module {
  void* handle = nullptr;
  decltype(&impactfe_mumps_start) start = nullptr;
  decltype(&impactfe_mumps_rank) rank = nullptr;
  decltype(&impactfe_mumps_size) size = nullptr;
  decltype(&impactfe_mumps_create) create = nullptr;
  decltype(&impactfe_mumps_destroy) destroy = nullptr;
  decltype(&impactfe_mumps_analyze) analyze = nullptr;
  decltype(&impactfe_mumps_factorize) factorize = nullptr;
  decltype(&impactfe_mumps_solve) solve = nullptr;
  decltype(&impactfe_mumps_column_owners) column_owners = nullptr;
  decltype(&impactfe_mumps_counters) counters = nullptr;
  decltype(&impactfe_mumps_max_int) max_int = nullptr;
  decltype(&impactfe_mumps_abort) abort = nullptr;
  decltype(&impactfe_mumps_stop) stop = nullptr;
  decltype(&impactfe_mumps_broadcast) broadcast = nullptr;
  decltype(&impactfe_mumps_agree) agree = nullptr;
  decltype(&impactfe_mumps_set_failing) set_failing = nullptr;
  decltype(&impactfe_mumps_share_owned) share_owned = nullptr;
  decltype(&impactfe_mumps_all_doubles) all_doubles = nullptr;
  MumpsModuleOptions options;
};
Module module;

/// Where the module may be: $IMPACTFE_MUMPS_MODULE, next to the executable (the build tree),
/// then ../lib/impactfe relative to it (an installation).
std::vector<std::filesystem::path> module_candidates() {
  std::vector<std::filesystem::path> out;
  if (const char* env = std::getenv("IMPACTFE_MUMPS_MODULE")) out.emplace_back(env);
  std::error_code ec;
  const auto exe = std::filesystem::read_symlink("/proc/self/exe", ec);
  if (!ec) {
    out.push_back(exe.parent_path() / "libimpactfe_mumps.so");
    out.push_back(exe.parent_path().parent_path() / "lib" / "impactfe" / "libimpactfe_mumps.so");
  }
  return out;
}

template <typename F>
void bind(F& f, const char* name) {
  f = reinterpret_cast<F>(dlsym(module.handle, name));
  if (!f) throw std::runtime_error(fmt::format("--solver mumps: the module lacks {}", name));
}

bool files_shared = false;  // share_rank0_files(true) in force

void broadcast_raw(void* data, long long bytes, int root = 0) {
  if (module.broadcast(data, bytes, root) != 0)
    throw std::runtime_error(fmt::format("MPI: a broadcast from rank {} failed", root));
}

/// core/files.h hooks of share_rank0_files: rank 0 asks its disk, every rank gets the answer.
bool shared_file_exists(const std::string& path, bool exists_only) {
  int found = process_rank() == 0 ? local_file_exists(path, exists_only) : 0;
  broadcast_raw(&found, sizeof(found));
  return found != 0;
}
std::optional<std::string> shared_read_file(const std::string& path, const ReadLimits& limits) {
  std::optional<std::string> text;
  // size: the bytes, -1 no such file, -2 - line a file beyond `limits` (OversizedFileError on
  // every rank alike).
  long long size = -1;
  if (process_rank() == 0) {
    try {
      text = local_read_file(path, limits);
      if (text) size = static_cast<long long>(text->size());
    } catch (const OversizedFileError& e) {
      size = -2 - e.line();
    }
  }
  broadcast_raw(&size, sizeof(size));
  if (size <= -2) {
    const int line = static_cast<int>(-2 - size);
    throw OversizedFileError(path, line, line > 0 ? limits.max_line : limits.max_bytes);
  }
  if (size < 0) return std::nullopt;
  if (!text) text.emplace(static_cast<std::size_t>(size), '\0');
  broadcast_raw(text->data(), size);
  return text;
}

/// Throws again, as impactfe's own exception, what a module call reported.
[[noreturn]] void rethrow(const MumpsModuleError& e) {
  const std::string what(e.message);
  switch (e.kind) {
    case MumpsModuleError::kSingular:
      throw SingularMatrixError(e.row, what);
    case MumpsModuleError::kOutOfMemory:
      throw std::bad_alloc();
    case MumpsModuleError::kLogic:
      throw std::logic_error(what);
    default:
      throw std::runtime_error(what);
  }
}

/// The module's MUMPS solver behind LinearSolver: every call goes through the module's C
/// interface (mumps_module_api.h), which returns an exception as a description.
class ModuleSolver final : public LinearSolver {
 public:
  ModuleSolver() {
    MumpsModuleError error;
    solver_ = module.create(&module.options, &error);
    if (solver_ == nullptr) rethrow(error);
  }
  ~ModuleSolver() override { module.destroy(solver_, std::uncaught_exceptions() > 0 ? 1 : 0); }
  ModuleSolver(const ModuleSolver&) = delete;
  ModuleSolver& operator=(const ModuleSolver&) = delete;

  void analyze_pattern(const SparseMatrix& lower) override {
    MumpsModuleError error;
    done(module.analyze(solver_, &lower, &error), error);
  }
  void factorize(const SparseMatrix& lower) override {
    MumpsModuleError error;
    done(module.factorize(solver_, &lower, &error), error);
  }
  VectorXd solve(const VectorXd& b) override {
    VectorXd x(b.size());
    MumpsModuleError error;
    done(module.solve(solver_, b.data(), x.data(), b.size(), 1, &error), error);
    return x;
  }
  MatrixXd solve(const MatrixXd& B) override {
    MatrixXd X(B.rows(), B.cols());
    MumpsModuleError error;
    done(module.solve(solver_, B.data(), X.data(), B.rows(), B.cols(), &error), error);
    return X;
  }
  std::string name() const override { return "MUMPS"; }
  std::vector<int> column_owners(const SparseMatrix& lower) const override {
    std::vector<int> owners(static_cast<std::size_t>(lower.cols()));
    MumpsModuleError error;
    const int found = module.column_owners(solver_, &lower, owners.data(), &error);
    if (found < 0) rethrow(error);
    if (found == 0) owners.clear();
    return owners;
  }

 private:
  /// The counters after a call (also after one that failed), then its exception if any.
  void done(int status, const MumpsModuleError& error) {
    module.counters(solver_, &counters_, &negative_pivots_, &first_negative_row_);
    if (status != 0) rethrow(error);
  }

  void* solver_ = nullptr;
};

std::unique_ptr<LinearSolver> make_mumps_solver() {
  return std::make_unique<ModuleSolver>();
}

}  // namespace

void start_parallel_backend(const ParallelSettings& settings) {
  if (module.handle) return;
  std::string errors;
  for (const auto& path : module_candidates()) {
    if (!std::filesystem::exists(path)) continue;
    // RTLD_GLOBAL: Open MPI's own plugins resolve libmpi's symbols through the global scope.
    module.handle = dlopen(path.c_str(), RTLD_NOW | RTLD_GLOBAL);
    if (module.handle) break;
    errors += fmt::format("\n  {}: {}", path.string(), dlerror());
  }
  if (!module.handle)
    throw std::runtime_error(fmt::format(
        "--solver mumps: cannot load libimpactfe_mumps.so (impactfe was built without MUMPS, or "
        "the MPI/MUMPS libraries are missing: scripts/install-deps.sh installs them){}",
        errors));
  bind(module.start, "impactfe_mumps_start");
  bind(module.rank, "impactfe_mumps_rank");
  bind(module.size, "impactfe_mumps_size");
  bind(module.create, "impactfe_mumps_create");
  bind(module.destroy, "impactfe_mumps_destroy");
  bind(module.analyze, "impactfe_mumps_analyze");
  bind(module.factorize, "impactfe_mumps_factorize");
  bind(module.solve, "impactfe_mumps_solve");
  bind(module.column_owners, "impactfe_mumps_column_owners");
  bind(module.counters, "impactfe_mumps_counters");
  bind(module.max_int, "impactfe_mumps_max_int");
  bind(module.abort, "impactfe_mumps_abort");
  bind(module.stop, "impactfe_mumps_stop");
  bind(module.broadcast, "impactfe_mumps_broadcast");
  bind(module.agree, "impactfe_mumps_agree");
  bind(module.set_failing, "impactfe_mumps_set_failing");
  bind(module.share_owned, "impactfe_mumps_share_owned");
  bind(module.all_doubles, "impactfe_mumps_all_doubles");
  module.options.refine = settings.refine;
  module.options.out_of_core = settings.out_of_core;
  fmt::format_to_n(module.options.ooc_directory, sizeof(module.options.ooc_directory) - 1, "{}",
                   settings.ooc_directory);
  if (module.start() != 0) throw std::runtime_error("--solver mumps: MPI_Init failed");
  set_sparse_solver_factory(&make_mumps_solver);
}

bool parallel_backend_active() {
  return module.handle != nullptr && module.stop != nullptr;
}

int process_rank() {
  return parallel_backend_active() ? module.rank() : 0;
}
int process_count() {
  return parallel_backend_active() ? module.size() : 1;
}

int max_over_ranks(int value) {
  return parallel_backend_active() ? module.max_int(value) : value;
}

void share_owned_values(double* values, int n, const std::vector<int>& owner) {
  if (!parallel_backend_active() || process_count() == 1) return;
  if (static_cast<int>(owner.size()) != n || module.share_owned(values, n, owner.data()) != 0)
    throw std::runtime_error("MPI: sharing the owned entries of a vector failed");
}

std::vector<double> values_of_all_ranks(double value) {
  if (!parallel_backend_active() || process_count() == 1) return {value};
  std::vector<double> out(static_cast<std::size_t>(process_count()));
  if (module.all_doubles(value, out.data()) != 0)
    throw std::runtime_error("MPI: gathering a value from every rank failed");
  return out;
}

void abort_all_ranks(int code) {
  if (parallel_backend_active()) module.abort(code);
  std::exit(code);
}

std::optional<int> agree_exit_status(int status, double wait_seconds) {
  if (!parallel_backend_active()) return status;
  int agreed = status;
  if (module.agree(status, wait_seconds, &agreed) != 0) return std::nullopt;
  return agreed;
}

void note_local_failure() {
  if (parallel_backend_active()) module.set_failing();
}

void broadcast_from_rank0(std::string& data) {
  broadcast_from_rank(data, 0);
}

void broadcast_from_rank(std::string& data, int root) {
  if (!parallel_backend_active() || process_count() == 1) return;
  long long size = static_cast<long long>(data.size());
  broadcast_raw(&size, sizeof(size), root);
  data.resize(static_cast<std::size_t>(size));
  broadcast_raw(data.data(), size, root);
}

void share_rank0_files(bool on) {
  files_shared = on && parallel_backend_active() && process_count() > 1;
  if (files_shared)
    set_file_hooks(&shared_file_exists, &shared_read_file);
  else
    set_file_hooks(nullptr, nullptr);
}

RankLocalWork::RankLocalWork(bool alone)
    : active_(alone && parallel_backend_active()), files_shared_(files_shared) {
  if (!active_) return;
  set_sparse_solver_factory(nullptr);
  set_file_hooks(nullptr, nullptr);
}

RankLocalWork::~RankLocalWork() {
  if (!active_) return;
  set_sparse_solver_factory(&make_mumps_solver);
  if (files_shared_) set_file_hooks(&shared_file_exists, &shared_read_file);
}

void stop_parallel_backend() {
  if (!parallel_backend_active()) return;
  share_rank0_files(false);
  set_sparse_solver_factory(nullptr);
  module.stop();
  module.stop = nullptr;  // the module stays mapped (Open MPI does not support unloading)
}

}  // namespace impactfe
