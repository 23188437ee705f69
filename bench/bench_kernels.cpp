// Kernel micro-benchmarks: element tangent/mass evaluation (Shell4 small and large deflection,
// Brick8, Spar), assembly of the effective matrix of an n x n SHELL63 plate, and CHOLMOD
// factorization and solve of that matrix. Models are built from deck text (modern dialect), so
// the elements are exactly those the CLI creates.
#include <benchmark/benchmark.h>

#include <Eigen/Geometry>

#include <memory>
#include <set>
#include <sstream>
#include <string>

#include "analysis/structure.h"
#include "assembly/assembler.h"
#include "assembly/dof_map.h"
#include "deck/deck_reader.h"
#include "linalg/linear_solver.h"
#include "linalg/solver_support.h"
#include "linalg/supernodal_substitution.h"
#include "stream_sum.h"

namespace impactfe {
namespace {

/// SHELL63 plate of n x n quads (10 in square, t = 0.1 in, steel), clamped along x = 0.
std::string plate_deck(int n, bool nlgeom, bool triangles = false) {
  std::ostringstream s;
  s << "/PREP7\nET,1,SHELL63\nR,1,0.1\nMP,EX,1,30E6\nMP,PRXY,1,0.3\nMP,DENS,1,7.3E-4\n";
  const double h = 10.0 / n;
  auto id = [n](int i, int j) { return 1 + i + j * (n + 1); };
  for (int j = 0; j <= n; ++j)
    for (int i = 0; i <= n; ++i) s << "N," << id(i, j) << "," << i * h << "," << j * h << ",0\n";
  for (int j = 0; j < n; ++j)
    for (int i = 0; i < n; ++i)
      s << "E," << id(i, j) << "," << id(i + 1, j) << "," << id(i + 1, j + 1) << ","
        << (triangles ? id(i + 1, j + 1) : id(i, j + 1)) << "\n";
  s << "FINISH\n/SOLU\nANTYPE,TRANS\nTRNOPT,FULL\nNLGEOM," << (nlgeom ? "ON" : "OFF") << "\n";
  for (int j = 0; j <= n; ++j) s << "D," << id(0, j) << ",ALL\n";
  s << "TIME,1E-3\nNSUBST,1\nSOLVE\nFINISH\n";
  return s.str();
}

const char* kBrickDeck = R"(/PREP7
ET,1,SOLID185
MP,EX,1,30E6
MP,PRXY,1,0.3
MP,DENS,1,7.3E-4
N,1,0,0,0
N,2,1,0,0
N,3,1,1,0
N,4,0,1,0
N,5,0,0,1
N,6,1,0,1
N,7,1,1,1
N,8,0,1,1
E,1,2,3,4,5,6,7,8
FINISH
/SOLU
ANTYPE,TRANS
NLGEOM,OFF
D,1,ALL
TIME,1E-3
SOLVE
FINISH
)";

const char* kSparDeck = R"(/PREP7
ET,1,LINK180
R,1,0.1
MP,EX,1,30E6
MP,DENS,1,7.3E-4
N,1,0,0,0
N,2,8.66,-5,0
E,1,2
FINISH
/SOLU
ANTYPE,TRANS
NLGEOM,ON
D,1,ALL
TIME,1E-3
SOLVE
FINISH
)";

/// A parsed deck and its solvable structure (first analysis, first load step).
struct Built {
  Job job;
  std::unique_ptr<Structure> structure;
  std::unique_ptr<DofMap> dofs;
  explicit Built(const std::string& text) : job(read_deck_text(text, "bench.inp")) {
    const Job::Step& step = job.steps.front();
    const AnalysisRequest& a = *step.analysis;
    structure =
        std::make_unique<Structure>(*step.model_snapshot, a.options, RunSettings{}, &a.load_steps);
    dofs = std::make_unique<DofMap>(structure->elements(),
                                    structure->constraints_of(a.load_steps.front()));
  }
};

/// Element-level: tangent (K_T and f_int) at a small deformed state, or (rotated) after a
/// rigid rotation of 0.8 rad about a skew axis of the whole element plus a few per cent of
/// deformation (the co-rotational shell's usual state in an impact).
void element_tangent(benchmark::State& state, const std::string& deck, bool large,
                     bool rotated = false) {
  // Two states a round-off apart, alternated: an element that keeps the state of its last
  // evaluation (the co-rotational triangle) forms each tangent anew, as in a Newton iteration.
  Built b(deck);
  const Element& e = *b.structure->elements().front();
  ElementContext ctx = b.structure->context();
  ctx.large_deflection = large;
  ctx.stress_stiffening = large;
  Eigen::VectorXd u = 1e-3 * Eigen::VectorXd::LinSpaced(e.n_dofs(), -1.0, 1.0);
  if (rotated) {
    const Eigen::AngleAxisd rot(0.8, Eigen::Vector3d(0.2, 1.0, 0.4).normalized());
    const std::vector<DofKey>& dofs = e.dofs();
    for (std::size_t i = 0; i + 5 < dofs.size(); i += 6) {
      const Eigen::Vector3d x = b.structure->model().nodes.at(dofs[i].node).x;
      const int j = static_cast<int>(i);
      u.segment<3>(j) = rot * x - x + 0.03 * u.segment<3>(j) / 1e-3;
      u.segment<3>(j + 3) = rot.angle() * rot.axis() + 0.05 * u.segment<3>(j + 3) / 1e-3;
    }
  }
  Eigen::VectorXd u2 = u;
  u2(0) += 1e-12;
  Eigen::MatrixXd K;
  Eigen::VectorXd f;
  bool second = false;
  for (auto _ : state) {
    e.tangent(ctx, second ? u2 : u, K, f);
    second = !second;
    benchmark::DoNotOptimize(K.data());
    benchmark::DoNotOptimize(f.data());
  }
}

void element_mass(benchmark::State& state, const std::string& deck) {
  Built b(deck);
  const Element& e = *b.structure->elements().front();
  Eigen::MatrixXd M;
  for (auto _ : state) {
    e.mass(b.structure->context(), M);
    benchmark::DoNotOptimize(M.data());
  }
}

void BM_Shell4TangentSmall(benchmark::State& s) {
  element_tangent(s, plate_deck(1, false), false);
}
void BM_Shell4TangentLarge(benchmark::State& s) {
  element_tangent(s, plate_deck(1, true), true);
}
void BM_Shell4TangentLargeRotated(benchmark::State& s) {
  element_tangent(s, plate_deck(1, true), true, true);
}
// The thesis helmet's element: a SHELL63 triangle (K = L) under large deflection, which takes
// the co-rotational triangle's closed forms (elements/corotational_triangle.h).
void BM_Shell3TangentLargeRotated(benchmark::State& s) {
  element_tangent(s, plate_deck(1, true, true), true, true);
}
void BM_Shell4Mass(benchmark::State& s) {
  element_mass(s, plate_deck(1, false));
}
void BM_Brick8Tangent(benchmark::State& s) {
  element_tangent(s, kBrickDeck, false);
}
// Large deflection (total Lagrangian), with the incompatible modes and without them (SOLID45
// KEYOPT(1) = 1, the helmet's bricks).
void BM_Brick8TangentLarge(benchmark::State& s) {
  std::string deck = kBrickDeck;
  deck.replace(deck.find("ET,1,SOLID185"), 13, "ET,1,45");
  element_tangent(s, deck, true);
}
void BM_Brick8TangentLargeNoExtraShapes(benchmark::State& s) {
  std::string deck = kBrickDeck;
  deck.replace(deck.find("ET,1,SOLID185"), 13, "ET,1,45,1");
  element_tangent(s, deck, true);
}
void BM_Brick8Mass(benchmark::State& s) {
  element_mass(s, kBrickDeck);
}
void BM_SparTangentSmall(benchmark::State& s) {
  element_tangent(s, kSparDeck, false);
}
void BM_SparTangentLarge(benchmark::State& s) {
  element_tangent(s, kSparDeck, true);
}
void BM_SparMass(benchmark::State& s) {
  element_mass(s, kSparDeck);
}
BENCHMARK(BM_Shell4TangentSmall);
BENCHMARK(BM_Shell4TangentLarge);
BENCHMARK(BM_Shell4TangentLargeRotated);
BENCHMARK(BM_Shell3TangentLargeRotated);
BENCHMARK(BM_Shell4Mass);
BENCHMARK(BM_Brick8Tangent);
BENCHMARK(BM_Brick8TangentLarge);
BENCHMARK(BM_Brick8TangentLargeNoExtraShapes);
BENCHMARK(BM_Brick8Mass);
BENCHMARK(BM_SparTangentSmall);
BENCHMARK(BM_SparTangentLarge);
BENCHMARK(BM_SparMass);

/// Newmark (beta = 1/4) effective-matrix coefficients for dt = 5e-5 s.
IntegrationCoefficients newmark_coefficients() {
  const double dt = 5e-5;
  IntegrationCoefficients c;
  c.cK = 1.0;
  c.cM = 1.0 / (0.25 * dt * dt);
  c.cC = 0.5 / (0.25 * dt);
  return c;
}

/// Assembly of K_eff (and f_int) of an n x n plate; arg 1 selects NLGEOM (elements re-evaluated).
void BM_AssemblePlate(benchmark::State& state) {
  const int n = static_cast<int>(state.range(0));
  const bool large = state.range(1) != 0;
  Built b(plate_deck(n, large));
  Assembler assembler(b.structure->elements(), *b.dofs, b.structure->context());
  SparseMatrix K = assembler.pattern().zero_matrix();
  VectorXd u = VectorXd::Constant(b.dofs->n_active(), 1e-4);
  VectorXd v = VectorXd::Zero(b.dofs->n_active());
  VectorXd f;
  Assembler::Output out;
  out.effective = &K;
  out.internal_force = &f;
  for (auto _ : state) {
    assembler.assemble(newmark_coefficients(), u, v, out);
    benchmark::DoNotOptimize(K.valuePtr());
  }
  state.counters["free_dofs"] = b.dofs->n_free();
  state.counters["nnz_lower"] = static_cast<double>(K.nonZeros());
  state.SetItemsProcessed(state.iterations() * n * n);  // elements per second
}
BENCHMARK(BM_AssemblePlate)
    ->Args({20, 0})
    ->Args({40, 0})
    ->Args({80, 0})
    ->Args({20, 1})
    ->Args({40, 1})
    ->Unit(benchmark::kMillisecond);

/// The effective matrix of an n x n plate, assembled once.
struct PlateSystem {
  Built b;
  SparseMatrix K;
  explicit PlateSystem(int n) : b(plate_deck(n, false)) {
    Assembler assembler(b.structure->elements(), *b.dofs, b.structure->context());
    K = assembler.pattern().zero_matrix();
    VectorXd u = VectorXd::Zero(b.dofs->n_active());
    Assembler::Output out;
    out.effective = &K;
    assembler.assemble(newmark_coefficients(), u, u, out);
  }
};

void BM_CholmodAnalyze(benchmark::State& state) {
  PlateSystem p(static_cast<int>(state.range(0)));
  for (auto _ : state) {
    auto solver = make_linear_solver(static_cast<int>(p.K.rows()), LinearSolverKind::Cholmod);
    solver->analyze_pattern(p.K);
  }
  state.counters["free_dofs"] = static_cast<double>(p.K.rows());
  // Sizes from the solver's counters (nnz(L) of the analysis, bytes a solve reads).
  auto solver = make_linear_solver(static_cast<int>(p.K.rows()), LinearSolverKind::Cholmod);
  solver->factorize(p.K);
  state.counters["nnz_A_lower"] = static_cast<double>(solver->counters().matrix_nonzeros);
  state.counters["nnz_L"] = static_cast<double>(solver->counters().factor_nonzeros);
  state.counters["factor_bytes"] = static_cast<double>(solver->counters().factor_bytes);
}

void BM_CholmodFactorize(benchmark::State& state) {
  PlateSystem p(static_cast<int>(state.range(0)));
  auto solver = make_linear_solver(static_cast<int>(p.K.rows()), LinearSolverKind::Cholmod);
  solver->analyze_pattern(p.K);
  for (auto _ : state) solver->factorize(p.K);
  state.counters["free_dofs"] = static_cast<double>(p.K.rows());
}

void BM_CholmodSolve(benchmark::State& state) {
  PlateSystem p(static_cast<int>(state.range(0)));
  auto solver = make_linear_solver(static_cast<int>(p.K.rows()), LinearSolverKind::Cholmod);
  solver->analyze_pattern(p.K);
  solver->factorize(p.K);
  VectorXd rhs = VectorXd::Ones(p.K.rows());
  for (auto _ : state) {
    VectorXd x = solver->solve(rhs);
    benchmark::DoNotOptimize(x.data());
  }
  state.counters["free_dofs"] = static_cast<double>(p.K.rows());
}
/// One forward and one back substitution with the plate's supernodal LLᵀ factor: CHOLMOD's own
/// solve (range(1) = 0: cholmod_solve2 with kept workspaces, BLAS threads as configured)
/// against supernodal_substitution.h (1; 2: the forward substitution only, 3: the back one);
/// 4 reads the factor's values twice and solves nothing (the bandwidth floor measured on the
/// same memory); 5: SubtreeSubstitution, the subtrees on the threads of --threads (the
/// benchmark's threads::set_max_threads: all cores). bytes_per_second counts the factor twice
/// in every mode.
void BM_SupernodalSolve(benchmark::State& state) {
  PlateSystem p(static_cast<int>(state.range(0)));
  cholmod_common common;
  cholmod_start(&common);
  common.supernodal = CHOLMOD_SUPERNODAL;
  common.final_ll = 1;
  cholmod_sparse a = solver_support::cholmod_lower_view(p.K);
  cholmod_factor* factor = cholmod_analyze(&a, &common);
  cholmod_factorize(&a, factor, &common);
  const auto n = static_cast<size_t>(p.K.rows());
  VectorXd rhs = VectorXd::Ones(p.K.rows());
  cholmod_dense b{};
  b.nrow = b.nzmax = b.d = n;
  b.ncol = 1;
  b.x = rhs.data();
  b.xtype = CHOLMOD_REAL;
  b.dtype = CHOLMOD_DOUBLE;
  cholmod_dense *x = nullptr, *y = nullptr, *e = nullptr;
  const SupernodalLayout layout = solver_support::supernodal_layout(factor);
  std::vector<double> work;
  SubtreeSubstitution subtrees;
  subtrees.plan(layout);
  VectorXd z = rhs;
  for (auto _ : state) {
    if (state.range(1) == 0) {
      cholmod_solve2(CHOLMOD_L, factor, &b, nullptr, &x, nullptr, &y, &e, &common);
      cholmod_solve2(CHOLMOD_Lt, factor, &b, nullptr, &x, nullptr, &y, &e, &common);
      benchmark::DoNotOptimize(x->x);
    } else if (state.range(1) == 4) {
      // The floor: the factor's values read twice (no solve).
      const auto* v = static_cast<const double*>(factor->x);
      double sum = bench::stream_sum(v, factor->xsize) + bench::stream_sum(v, factor->xsize);
      benchmark::DoNotOptimize(sum);
    } else if (state.range(1) == 5) {
      z = rhs;
      subtrees.forward(layout, z.data());
      subtrees.back(layout, z.data());
      benchmark::DoNotOptimize(z.data());
    } else {
      z = rhs;
      if (state.range(1) != 3) forward_substitution(layout, z.data(), work);
      if (state.range(1) != 2) back_substitution(layout, z.data(), work);
      benchmark::DoNotOptimize(z.data());
    }
  }
  const double bytes = static_cast<double>(factor->xsize * sizeof(double) + factor->ssize * 4);
  state.SetBytesProcessed(static_cast<int64_t>(2.0 * bytes) *
                          static_cast<int64_t>(state.iterations()));
  state.counters["factor_MB"] = bytes / 1e6;
  if (state.range(1) == 5) {
    state.counters["groups"] = subtrees.groups();
    state.counters["serial"] = subtrees.serial_fraction();
  }
  for (cholmod_dense** d : {&x, &y, &e})
    if (*d) cholmod_free_dense(d, &common);
  cholmod_free_factor(&factor, &common);
  cholmod_finish(&common);
}
BENCHMARK(BM_SupernodalSolve)
    ->Args({40, 0})
    ->Args({40, 1})
    ->Args({80, 0})
    ->Args({80, 1})
    ->Args({80, 4})
    ->Args({160, 0})
    ->Args({160, 1})
    ->Args({160, 2})
    ->Args({160, 3})
    ->Args({160, 4})
    ->Args({160, 5})
    ->Args({80, 5})
    ->Unit(benchmark::kMillisecond);

BENCHMARK(BM_CholmodAnalyze)->Arg(20)->Arg(40)->Arg(80)->Unit(benchmark::kMillisecond);
BENCHMARK(BM_CholmodFactorize)->Arg(20)->Arg(40)->Arg(80)->Unit(benchmark::kMillisecond);
BENCHMARK(BM_CholmodSolve)->Arg(20)->Arg(40)->Arg(80)->Unit(benchmark::kMillisecond);

}  // namespace
}  // namespace impactfe

BENCHMARK_MAIN();
