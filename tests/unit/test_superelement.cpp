// Superelement generation (Guyan), MATRIX50 use and expansion on a small spar + shell structure.
// Reference solutions are the full (unreduced) model solved with the same elements: static
// condensation is exact for static loads (Guyan 1965; Cook et al. §10.10), and the Guyan
// frequencies are Rayleigh-Ritz upper bounds of the full model's.
#include <gtest/gtest.h>

#include <Eigen/Dense>
#include <Eigen/Eigenvalues>
#include <cmath>
#include <filesystem>
#include <map>
#include <numbers>
#include <set>
#include <string>

#include "analysis/structure.h"
#include "analysis/superelement_expansion.h"
#include "analysis/superelement_generation.h"
#include "assembly/loads.h"
#include "core/log.h"
#include "deck/deck_reader.h"
#include "elements/superelement.h"

namespace impactfe::test_superelement {
namespace {

namespace fs = std::filesystem;

// ---- decks ----------------------------------------------------------------------------------

/// 4 x 4 nodes on a 0.5 in grid, node id 1 + i + 4 j; z = (x² + y²)/4 when `curved`. Nine
/// SHELL63 quads (t = 0.06, E = 2.6e6, ρ = 1.965e-4: the thesis helmet material) and one LINK180
/// diagonal spar 1 -> 16 (A = 0.02, E = 1e7, ρ = 2.588e-4).
std::string geometry(bool curved) {
  std::string s =
      "/PREP7\nET,1,SHELL63\nET,2,LINK180\nR,1,0.06\nR,2,0.02\n"
      "MP,EX,1,2.6E6\nMP,PRXY,1,0.25\nMP,DENS,1,1.965E-4\n"
      "MP,EX,2,1E7\nMP,PRXY,2,0.3\nMP,DENS,2,2.588E-4\n";
  for (int j = 0; j < 4; ++j)
    for (int i = 0; i < 4; ++i) {
      const double x = 0.5 * i, y = 0.5 * j;
      const double z = curved ? (x * x + y * y) / 4.0 : 0.0;
      s += "N," + std::to_string(1 + i + 4 * j) + "," + std::to_string(x) + "," +
           std::to_string(y) + "," + std::to_string(z) + "\n";
    }
  s += "TYPE,1\nREAL,1\nMAT,1\n";
  for (int j = 0; j < 3; ++j)
    for (int i = 0; i < 3; ++i) {
      const int n = 1 + i + 4 * j;
      s += "E," + std::to_string(n) + "," + std::to_string(n + 1) + "," + std::to_string(n + 5) +
           "," + std::to_string(n + 4) + "\n";
    }
  s += "TYPE,2\nREAL,2\nMAT,2\nE,1,16\n";
  return s;
}

/// Loads of the comparison: forces on master DOFs and a frame acceleration with all three
/// components (the X and Y parts cannot be carried by the UZ/UX masters through M_r alone).
const char* kLoads = "F,16,FZ,-2.5\nF,14,FZ,1.0\nF,16,FX,3.0\nACEL,120,-80,386.4\n";
const char* kMasters = "M,13,UZ,16,1\nM,16,UX\nM,6,UZ\nM,11,UZ\n";
const char* kClamp = "D,1,ALL,,,4,1\n";

Job parse(const std::string& text) {
  return read_deck_text(text, "test.inp");
}

// ---- a small dense solver over the library's numbering --------------------------------------

struct Solved {
  std::map<DofKey, double> u;
  std::unique_ptr<DofMap> dofs;
  VectorXd u_all;
};

/// Static solve K_ff u_f = f_f (dense LDLᵀ), loads = F + frame-acceleration load.
Solved solve_static(const Structure& s, const LoadStep& step) {
  Solved out;
  out.dofs = std::make_unique<DofMap>(s.elements(), s.constraints_of(step));
  const Assembler assembler(s.elements(), *out.dofs, s.context());
  const int nf = out.dofs->n_free();
  const MatrixXd K = MatrixXd(assembler.stiffness_matrix(VectorXd::Zero(out.dofs->n_active())));
  const LoadPoint at{&step, nullptr, 1.0};
  const VectorXd f = nodal_forces(*out.dofs, at) +
                     inertia_load(s.elements(), *out.dofs, s.context(), frame_acceleration(at));
  out.u_all = VectorXd::Zero(out.dofs->n_active());
  out.u_all.head(nf) = K.topLeftCorner(nf, nf).ldlt().solve(f.head(nf));
  for (int i = 0; i < out.dofs->n_active(); ++i) out.u[out.dofs->key(i)] = out.u_all(i);
  return out;
}

/// Lowest generalized eigenvalues of (K, M) as frequencies in Hz.
std::vector<double> frequencies(const MatrixXd& K, const MatrixXd& M, int n) {
  Eigen::GeneralizedSelfAdjointEigenSolver<MatrixXd> es(K, M);
  std::vector<double> f;
  for (int i = 0; i < n && i < es.eigenvalues().size(); ++i)
    f.push_back(std::sqrt(std::max(0.0, es.eigenvalues()(i))) / (2.0 * std::numbers::pi));
  return f;
}

class SuperelementTest : public ::testing::Test {
 protected:
  void SetUp() override {
    dir_ = fs::temp_directory_path() /
           ("impactfe_se_" + std::to_string(::testing::UnitTest::GetInstance()->random_seed()) +
            "_" + ::testing::UnitTest::GetInstance()->current_test_info()->name());
    fs::create_directories(dir_);
  }
  void TearDown() override { fs::remove_all(dir_); }

  /// Generates the superelement of `deck` (its first analysis) into dir_/name.sub.h5.
  std::string generate(const std::string& deck, const std::string& name,
                       GenerationSummary* summary_out = nullptr) {
    const Job job = parse(deck);
    const Job::Step& step = job.steps.at(0);
    Structure s(*step.model_snapshot, step.analysis->options, RunSettings{});
    GenerationSummary summary;
    const SuperelementData se = generate_superelement(s, *step.analysis, name, summary);
    const std::string path = (dir_ / (name + ".sub.h5")).string();
    write_superelement(path, se);
    if (summary_out) *summary_out = summary;
    return path;
  }

  fs::path dir_;
};

std::string generation_deck(bool curved) {
  return geometry(curved) + kMasters + "FINISH\n/SOLU\nANTYPE,SUBSTR\nSEOPT,plate,2\n" + kClamp +
         "SOLVE\nFINISH\n";
}

std::string use_deck(const SuperelementData& se, bool loads) {
  std::string s = "/PREP7\nET,1,MATRIX50\n";
  std::set<int> nodes;
  for (const auto& m : se.masters)
    if (nodes.insert(m.key.node).second)
      s += "N," + std::to_string(m.key.node) + "," + std::to_string(m.x(0)) + "," +
           std::to_string(m.x(1)) + "," + std::to_string(m.x(2)) + "\n";
  s += "TYPE,1\nSE,plate\nFINISH\n/SOLU\nANTYPE,STATIC\n";
  if (loads) s += kLoads;
  return s + "SOLVE\nFINISH\n";
}

// ---- tests ----------------------------------------------------------------------------------

TEST_F(SuperelementTest, StaticUsePassReproducesFullModelMastersExactly) {
  const std::string path = generate(generation_deck(/*curved=*/true), "plate");
  const SuperelementData se = read_superelement(path);
  ASSERT_EQ(se.n_masters(), 7);

  const Job full = parse(geometry(true) + "FINISH\n/SOLU\nANTYPE,STATIC\n" + kClamp + kLoads +
                         "SOLVE\nFINISH\n");
  Structure full_s(*full.steps[0].model_snapshot, full.steps[0].analysis->options, RunSettings{});
  const Solved reference = solve_static(full_s, full.steps[0].analysis->load_steps[0]);

  const Job use = parse(use_deck(se, true));
  RunSettings settings;
  settings.superelement_file = path;
  Structure use_s(*use.steps[0].model_snapshot, use.steps[0].analysis->options, settings);
  ASSERT_EQ(use_s.elements().size(), 1u);
  EXPECT_STREQ(use_s.elements()[0]->family(), "Superelement");
  const Solved reduced = solve_static(use_s, use.steps[0].analysis->load_steps[0]);

  double peak = 0.0;
  for (const auto& m : se.masters) peak = std::max(peak, std::abs(reference.u.at(m.key)));
  ASSERT_GT(peak, 1e-4);
  for (const auto& m : se.masters)
    EXPECT_NEAR(reduced.u.at(m.key), reference.u.at(m.key), 1e-10 * peak) << describe(m.key);
}

TEST_F(SuperelementTest, UnitAccelerationVectorsDifferFromMassTimesRigidMotionHere) {
  // With UZ/UX masters on a clamped curved shell the masters cannot represent a rigid Y (or X)
  // translation, so −M_r r a is not the reduced inertia load; g_d = TᵀM r_d is (spec U25).
  const SuperelementData se = read_superelement(generate(generation_deck(true), "plate"));
  const MatrixXd& M = *se.mass;
  for (int d : {0, 1}) {
    VectorXd r = VectorXd::Zero(se.n_masters());
    for (int k = 0; k < se.n_masters(); ++k)
      if (static_cast<int>(se.masters[k].key.dof) == d) r(k) = 1.0;
    const VectorXd via_mass = M * r;
    EXPECT_GT((via_mass - se.unit_acceleration.col(d)).norm(),
              0.01 * se.unit_acceleration.col(d).norm())
        << "direction " << d;
  }
}

TEST_F(SuperelementTest, GenerationLoadVectorReproducesStaticMasterDisplacements) {
  // Loads on slave DOFs during generation: K_r u_m = Tᵀ f holds for the full model's u_m.
  const std::string loads = "F,7,FZ,-4\nF,10,FY,2\nACEL,0,0,386.4\n";
  const std::string path =
      generate(geometry(true) + kMasters + "FINISH\n/SOLU\nANTYPE,SUBSTR\nSEOPT,plate,2\n" +
                   kClamp + loads + "SOLVE\nFINISH\n",
               "plate");
  const SuperelementData se = read_superelement(path);
  ASSERT_EQ(se.load_vectors.cols(), 1);
  const Job full =
      parse(geometry(true) + "FINISH\n/SOLU\nANTYPE,STATIC\n" + kClamp + loads + "SOLVE\n");
  Structure full_s(*full.steps[0].model_snapshot, full.steps[0].analysis->options, RunSettings{});
  const Solved reference = solve_static(full_s, full.steps[0].analysis->load_steps[0]);
  VectorXd um(se.n_masters());
  for (int k = 0; k < se.n_masters(); ++k) um(k) = reference.u.at(se.masters[k].key);
  const VectorXd um_reduced = se.stiffness.ldlt().solve(se.load_vectors.col(0));
  EXPECT_LT((um_reduced - um).norm(), 1e-10 * um.norm());

  // Expansion with the load-vector static correction gives every slave exactly.
  const SuperelementExpansion expansion(se);
  const VectorXd u = expansion.expand_displacement(um, Vec3::Zero(), {1.0});
  double worst = 0.0;
  for (int i = 0; i < expansion.dofs().n_active(); ++i)
    worst = std::max(worst, std::abs(u(i) - reference.u.at(expansion.dofs().key(i))));
  EXPECT_LT(worst, 1e-10 * reference.u_all.cwiseAbs().maxCoeff());
}

TEST_F(SuperelementTest, MatricesSymmetricAndMassSumsToStructureMass) {
  // Free-free flat plate + spar; masters UX UY UZ at three non-collinear nodes span the rigid
  // translations, so r_dᵀ M_r r_d = total mass = ρ_shell t A + ρ_spar A_spar L.
  GenerationSummary summary;
  const std::string path = generate(geometry(/*curved=*/false) +
                                        "M,1,UX,,,UY,UZ\nM,4,UX,,,UY,UZ\nM,16,UX,,,UY,UZ\n"
                                        "FINISH\n/SOLU\nANTYPE,SUBSTR\nSEOPT,plate,2\nSOLVE\n",
                                    "plate", &summary);
  const SuperelementData se = read_superelement(path);
  ASSERT_EQ(se.n_masters(), 9);
  ASSERT_TRUE(se.mass.has_value());
  const double k_scale = se.stiffness.cwiseAbs().maxCoeff();
  const double m_scale = se.mass->cwiseAbs().maxCoeff();
  EXPECT_LT((se.stiffness - se.stiffness.transpose()).cwiseAbs().maxCoeff(), 1e-12 * k_scale);
  EXPECT_LT((*se.mass - se.mass->transpose()).cwiseAbs().maxCoeff(), 1e-12 * m_scale);

  const double total = 1.965e-4 * 0.06 * 1.5 * 1.5 + 2.588e-4 * 0.02 * 1.5 * std::sqrt(2.0);
  for (int d = 0; d < 3; ++d) {
    VectorXd r = VectorXd::Zero(se.n_masters());
    for (int k = 0; k < se.n_masters(); ++k)
      if (static_cast<int>(se.masters[k].key.dof) == d) r(k) = 1.0;
    EXPECT_NEAR(r.dot(*se.mass * r), total, 1e-10 * total) << "direction " << d;
    // Masters span the translation: g_d = M_r r_d.
    EXPECT_LT((se.unit_acceleration.col(d) - *se.mass * r).norm(), 1e-10 * total);
    EXPECT_NEAR(summary.total_mass[d], total, 1e-10 * total);
    // Rigid translation costs no strain energy through K_r.
    EXPECT_LT((se.stiffness * r).norm(), 1e-8 * k_scale);
  }
}

TEST_F(SuperelementTest, ModalCondensationErrorOfTheCurvedShell) {
  const SuperelementData se = read_superelement(generate(generation_deck(true), "plate"));
  const Job full = parse(geometry(true) + "FINISH\n/SOLU\nANTYPE,MODAL\n" + kClamp + "SOLVE\n");
  Structure s(*full.steps[0].model_snapshot, full.steps[0].analysis->options, RunSettings{});
  const DofMap dofs(s.elements(), s.constraints_of(full.steps[0].analysis->load_steps[0]));
  const Assembler assembler(s.elements(), dofs, s.context());
  const int nf = dofs.n_free();
  const MatrixXd K =
      MatrixXd(assembler.stiffness_matrix(VectorXd::Zero(dofs.n_active()))).topLeftCorner(nf, nf);
  const MatrixXd M = MatrixXd(assembler.mass_matrix()).topLeftCorner(nf, nf);
  const std::vector<double> f_full = frequencies(K, M, 3);
  const std::vector<double> f_se = frequencies(se.stiffness, *se.mass, 3);
  for (int i = 0; i < 3; ++i) {
    const double error = f_se[i] / f_full[i] - 1.0;
    ::testing::Test::RecordProperty("mode" + std::to_string(i + 1) + "_condensation_error",
                                    std::to_string(error));
    std::printf("mode %d: full %.6g Hz, superelement %.6g Hz, condensation error %+.3f %%\n", i + 1,
                f_full[i], f_se[i], 100.0 * error);
    // Rayleigh-Ritz: the reduced (constrained) model can only be stiffer.
    EXPECT_GE(f_se[i], f_full[i] * (1.0 - 1e-9));
  }
  // Seven well-spread masters on a 3 x 3 mesh: the fundamental mode is captured to a few %.
  EXPECT_LT(f_se[0] / f_full[0] - 1.0, 0.05);
}

TEST_F(SuperelementTest, ExpansionOfStaticUsePassGivesFullDisplacementsAndStresses) {
  const std::string path = generate(generation_deck(true), "plate");
  const SuperelementData se = read_superelement(path);
  const Job full = parse(geometry(true) + "FINISH\n/SOLU\nANTYPE,STATIC\n" + kClamp + kLoads +
                         "SOLVE\nFINISH\n");
  Structure full_s(*full.steps[0].model_snapshot, full.steps[0].analysis->options, RunSettings{});
  const Solved reference = solve_static(full_s, full.steps[0].analysis->load_steps[0]);

  const Job use = parse(use_deck(se, true));
  RunSettings settings;
  settings.superelement_file = path;
  Structure use_s(*use.steps[0].model_snapshot, use.steps[0].analysis->options, settings);
  const Solved reduced = solve_static(use_s, use.steps[0].analysis->load_steps[0]);
  VectorXd um(se.n_masters());
  for (int k = 0; k < se.n_masters(); ++k) um(k) = reduced.u.at(se.masters[k].key);

  const SuperelementExpansion expansion(se);
  const Vec3 acel(120, -80, 386.4);
  const VectorXd zero = VectorXd::Zero(se.n_masters());
  const TimePoint p = expansion.time_point(1.0, um, zero, zero, acel);
  const double peak = reference.u_all.cwiseAbs().maxCoeff();
  ASSERT_EQ(expansion.node_ids().size(), 16u);
  for (std::size_t r = 0; r < expansion.node_ids().size(); ++r)
    for (Dof d : kAllDofs) {
      const DofKey key{expansion.node_ids()[r], d};
      EXPECT_NEAR(p.displacement(int(r), int(d)), reference.u.at(key), 1e-9 * peak)
          << describe(key);
    }
  // Element results of the expansion equal those of the full model at the full solution.
  const Assembler assembler(full_s.elements(), *reference.dofs, full_s.context());
  const auto full_results = full_s.element_results(assembler, reference.u_all,
                                                   VectorXd::Zero(reference.dofs->n_active()));
  ASSERT_EQ(p.element_results.size(), full_results.size());
  for (const auto& [family, table] : full_results) {
    const ElementResultTable& got = p.element_results.at(family);
    ASSERT_EQ(got.element_ids, table.element_ids);
    const double scale = std::max(1e-30, table.values.cwiseAbs().maxCoeff());
    const MatrixXd diff = (got.values - table.values).cwiseAbs();
    EXPECT_LT(diff.maxCoeff(), 1e-8 * scale) << family;
  }
  // Without the static correction the slaves miss their own gravity sag.
  const VectorXd u_plain = expansion.expand_displacement(um);
  double miss = 0.0;
  for (int i = 0; i < expansion.dofs().n_active(); ++i)
    miss = std::max(miss, std::abs(u_plain(i) - reference.u.at(expansion.dofs().key(i))));
  EXPECT_GT(miss, 1e-6 * peak);
}

TEST_F(SuperelementTest, FileRoundTripKeepsEverything) {
  const Job job = parse(generation_deck(true));
  Structure s(*job.steps[0].model_snapshot, job.steps[0].analysis->options, RunSettings{});
  GenerationSummary summary;
  const SuperelementData se = generate_superelement(s, *job.steps[0].analysis, "plate", summary);
  const std::string path = (dir_ / "rt.sub.h5").string();
  write_superelement(path, se);
  const SuperelementData back = read_superelement(path);
  EXPECT_EQ(back.name, "plate");
  EXPECT_EQ(back.matrices, 2);
  EXPECT_EQ(back.master_keys(), se.master_keys());
  EXPECT_EQ(back.slaves, se.slaves);
  EXPECT_EQ(back.constrained, se.constrained);
  EXPECT_EQ(back.stiffness, se.stiffness);
  EXPECT_EQ(*back.mass, *se.mass);
  EXPECT_FALSE(back.damping.has_value());
  EXPECT_EQ(back.unit_acceleration, se.unit_acceleration);
  EXPECT_EQ(back.transformation, se.transformation);
  EXPECT_EQ(back.model_text, se.model_text);
  EXPECT_EQ(summary.n_masters + summary.n_slaves + summary.n_constrained,
            16 * 6);  // every shell node carries 6 DOFs
  EXPECT_EQ(summary.n_constrained, 4 * 6);
}

TEST_F(SuperelementTest, UsePassWarnsWhenMasterNodeMoved) {
  const SuperelementData se = read_superelement(generate(generation_deck(true), "plate"));
  std::string deck = use_deck(se, false);
  // Move master node 16 by 1e-3 (> TOLER 1e-4).
  const std::string from = "N,16,1.500000,1.500000,1.125000";
  ASSERT_NE(deck.find(from), std::string::npos);
  deck.replace(deck.find(from), from.size(), "N,16,1.501000,1.500000,1.125000");
  const Job use = parse(deck);
  RunSettings settings;
  settings.superelement_file = (dir_ / "plate.sub.h5").string();
  Log::clear();
  Structure s(*use.steps[0].model_snapshot, use.steps[0].analysis->options, settings);
  bool warned = false;
  for (const auto& w : Log::warnings()) warned |= w.find("node 16") != std::string::npos;
  EXPECT_TRUE(warned);
}

TEST_F(SuperelementTest, GenerationRejectsNonZeroConstraintAndConstrainedMaster) {
  const Job nonzero = parse(geometry(true) + kMasters +
                            "FINISH\n/SOLU\nANTYPE,SUBSTR\nD,1,ALL,,,4,1\nD,5,UZ,0.1\nSOLVE\n");
  Structure s1(*nonzero.steps[0].model_snapshot, nonzero.steps[0].analysis->options, RunSettings{});
  GenerationSummary summary;
  EXPECT_THROW(generate_superelement(s1, *nonzero.steps[0].analysis, "x", summary), InputError);

  const Job master_fixed = parse(
      geometry(true) + "M,2,UZ\nM,16,UZ\nFINISH\n/SOLU\nANTYPE,SUBSTR\n" + kClamp + "SOLVE\n");
  Structure s2(*master_fixed.steps[0].model_snapshot, master_fixed.steps[0].analysis->options,
               RunSettings{});
  try {
    generate_superelement(s2, *master_fixed.steps[0].analysis, "x", summary);
    FAIL() << "expected an InputError";
  } catch (const InputError& e) {
    EXPECT_NE(std::string(e.what()).find("constrained"), std::string::npos) << e.what();
  }
}

TEST_F(SuperelementTest, MissingFileIsAnInputError) {
  EXPECT_THROW(read_superelement((dir_ / "none.sub.h5").string()), InputError);
}

}  // namespace
}  // namespace impactfe::test_superelement

namespace impactfe::test_superelement {
namespace {

TEST(SuperelementFile, VersionOneFilesAreStillRead) {
  // Written by impactfe before element types were stored by name only (format version 1: the
  // generation model listed "etype id name enum ..."): tests/decks/modern/se_generate_bar.inp.
  const std::string path = std::string(IMPACTFE_TEST_DECKS) + "/files/bar_format_v1.sub.h5";
  const SuperelementData se = read_superelement(path);
  ASSERT_EQ(se.n_masters(), 2);
  EXPECT_EQ(se.masters[0].key, (DofKey{1, Dof::UX}));
  EXPECT_NEAR(se.stiffness(0, 0), 3e6, 1e-6 * 3e6);  // EA/L of the 10-inch bar
  bool lumped = true, sstif = true;
  const Model m = deserialize_generation_model(se.model_text, lumped, sstif);
  ASSERT_EQ(m.element_types.size(), 1u);
  EXPECT_EQ(m.element_types.at(1).ansys_name, "LINK180");
  EXPECT_EQ(m.element_types.at(1).key(1),
            0);  // the enum integer was skipped, not read as KEYOPT(1)
  EXPECT_EQ(m.elements.size(), 10u);
  // A current file round-trips the model text through format version 2.
  EXPECT_NE(serialize_generation_model(m, false, false).find("etype 1 LINK180 0 0"),
            std::string::npos);
}

}  // namespace
}  // namespace impactfe::test_superelement
