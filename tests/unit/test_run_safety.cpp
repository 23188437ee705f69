// Results files are never lost, and input never hangs the reader: two runs of one job in one
// directory (the second refused at once, exit 1, naming the first's process; the first's file
// intact), jobnames that would leave the output directory, a deck that /INPUTs itself, a deck
// without line ends (/dev/zero). docs/reliability.md.
#include <fcntl.h>
#include <gtest/gtest.h>
#include <sys/stat.h>
#include <sys/wait.h>
#include <unistd.h>

#include <fmt/format.h>

#include <chrono>
#include <fstream>
#include <sstream>
#include <thread>

#include "../support/run_deck.h"
#include "core/files.h"
#include "core/job_lock.h"
#include "core/memory_budget.h"
#include "core/model.h"
#include "elements/model_memory.h"
#include "linalg/linear_solver.h"

namespace impactfe::test_run_safety {
namespace {

namespace fs = std::filesystem;

std::string read_text(const fs::path& path) {
  std::ifstream in(path);
  std::stringstream s;
  s << in.rdbuf();
  return s.str();
}

void write_text(const fs::path& path, const std::string& text) {
  std::ofstream(path) << text;
}

/// `impactfe run DECK -o DIR [extra...]` in a child process, its output to `output`.
pid_t start_run(const fs::path& deck, const fs::path& dir, const fs::path& output,
                const std::vector<std::string>& extra = {}) {
  std::vector<std::string> args{IMPACTFE_BINARY, "run", deck.string(), "-o", dir.string()};
  args.insert(args.end(), extra.begin(), extra.end());
  const pid_t pid = fork();
  if (pid != 0) return pid;
  const int fd = ::open(output.c_str(), O_WRONLY | O_CREAT | O_TRUNC, 0644);
  if (fd >= 0) {
    dup2(fd, 2);
    dup2(fd, 1);
  }
  std::vector<char*> argv;
  for (auto& a : args) argv.push_back(a.data());
  argv.push_back(nullptr);
  execv(IMPACTFE_BINARY, argv.data());
  _exit(127);
}

int wait_exit_status(pid_t pid) {
  int status = 0;
  waitpid(pid, &status, 0);
  if (WIFSIGNALED(status)) return 128 + WTERMSIG(status);
  return WEXITSTATUS(status);
}

/// The car crash (case 1, modern form) run long enough to be caught running: 5·10⁴ reduced
/// substeps, every 500th stored, and the expansion pass of the stored points.
std::string long_deck() {
  std::string deck = read_text(fs::path(IMPACTFE_TEST_DECKS) / "modern" / "crash1_modern.inp");
  const auto replace = [&deck](const std::string& from, const std::string& to) {
    const auto pos = deck.find(from);
    ASSERT_NE(pos, std::string::npos) << from;
    deck.replace(pos, from.size(), to);
  };
  replace("DELTIM,1E-4", "DELTIM,1E-6");
  replace("TIME,1E-4", "TIME,1E-6");
  replace("TIME,0.006", "TIME,0.05");
  replace("OUTRES,ALL,ALL", "OUTRES,ALL,500");
  return deck;
}

/// Every analysis of the file is complete and its stored points read back.
void expect_intact(const fs::path& results, int analyses) {
  ResultsReader r(results.string());
  const auto info = r.analyses();
  ASSERT_EQ(static_cast<int>(info.size()), analyses);
  for (const auto& a : info) {
    EXPECT_EQ(a.status, "complete") << "analysis " << a.index;
    ASSERT_GT(a.n_time_points, 0) << "analysis " << a.index;
    const TimePoint last = r.time_point(a.index, a.n_time_points - 1);
    EXPECT_DOUBLE_EQ(last.time, a.time_last);
  }
}

TEST(ConcurrentRuns, SecondRunOfTheJobIsRefusedAtOnceAndTheFirstFileStaysIntact) {
  const fs::path dir = testing::fresh_directory("concurrent_runs");
  const fs::path deck = dir / "job.inp";
  write_text(deck, long_deck());
  const fs::path out = dir / "out";
  const pid_t first = start_run(deck, out, dir / "first.txt");
  // The first run is writing its results when the second starts.
  const auto deadline = std::chrono::steady_clock::now() + std::chrono::seconds(120);
  while (!fs::exists(out / "job.h5") && std::chrono::steady_clock::now() < deadline)
    std::this_thread::sleep_for(std::chrono::milliseconds(5));
  ASSERT_TRUE(fs::exists(out / "job.lock"));
  const auto start = std::chrono::steady_clock::now();
  const int second = wait_exit_status(start_run(deck, out, dir / "second.txt"));
  const double refused_in =
      std::chrono::duration<double>(std::chrono::steady_clock::now() - start).count();
  int status = 0;
  const bool first_still_running = waitpid(first, &status, WNOHANG) == 0;
  const std::string err = read_text(dir / "second.txt");
  EXPECT_EQ(second, 1) << err;
  EXPECT_NE(err.find("another run (process " + std::to_string(first) + ")"), std::string::npos)
      << err;
  EXPECT_NE(err.find("job.lock"), std::string::npos) << err;
  EXPECT_LT(refused_in, 1.0);
  std::cout << "second run refused in " << refused_in << " s\n";
  const int first_status = first_still_running ? wait_exit_status(first) : WEXITSTATUS(status);
  ASSERT_TRUE(first_still_running) << "the first run ended before the second started";
  EXPECT_EQ(first_status, 0) << read_text(dir / "first.txt");
  expect_intact(out / "job.h5", 2);
  // The first run's log was not truncated by the second, and the lock is gone with the run.
  EXPECT_NE(read_text(out / "job.log").find("run summary"), std::string::npos);
  EXPECT_FALSE(fs::exists(out / "job.lock"));
  EXPECT_FALSE(fs::exists(out / "job.h5.creating"));
}

TEST(ConcurrentRuns, TwoRunsStartedTogetherLeaveOneIntactFile) {
  const fs::path dir = testing::fresh_directory("concurrent_start");
  const fs::path deck = dir / "job.inp";
  write_text(deck, long_deck());
  const fs::path out = dir / "out";
  const pid_t a = start_run(deck, out, dir / "a.txt");
  const pid_t b = start_run(deck, out, dir / "b.txt");
  const int sa = wait_exit_status(a), sb = wait_exit_status(b);
  EXPECT_EQ(std::min(sa, sb), 0) << read_text(dir / "a.txt") << read_text(dir / "b.txt");
  EXPECT_EQ(std::max(sa, sb), 1) << read_text(dir / "a.txt") << read_text(dir / "b.txt");
  const std::string refused = read_text(dir / (sa == 1 ? "a.txt" : "b.txt"));
  EXPECT_NE(refused.find("another run (process " + std::to_string(sa == 1 ? b : a) + ")"),
            std::string::npos)
      << refused;
  EXPECT_EQ(refused.find("HDF5"), std::string::npos) << refused;
  expect_intact(out / "job.h5", 2);
}

TEST(ConcurrentRuns, LockIsSharedWithinAProcessAndRemovedByTheLastHolder) {
  const fs::path dir = testing::fresh_directory("job_lock");
  const std::string results = (dir / "job.h5").string();
  {
    auto first = JobLock::acquire(results);
    auto again = JobLock::acquire(results);  // the run's own session: the same lock
    EXPECT_EQ(first.get(), again.get());
    EXPECT_EQ(read_text(dir / "job.lock"), std::to_string(::getpid()) + "\n");
  }
  EXPECT_FALSE(fs::exists(dir / "job.lock"));
  // A lock file left by a killed run (no lock held on it) is taken over.
  write_text(dir / "job.lock", "999999\n");
  EXPECT_NO_THROW(JobLock::acquire(results));
}

TEST(ConcurrentRuns, RerunReplacesTheResultsFileWhole) {
  // A new file is made under a temporary name and renamed into place: a reader of the old file
  // keeps reading the old file (its inode), never a truncated one.
  const fs::path dir = testing::fresh_directory("rerun");
  const fs::path deck = fs::path(IMPACTFE_TEST_DECKS) / "modern" / "crash1_modern.inp";
  ASSERT_EQ(wait_exit_status(start_run(deck, dir, dir / "1.txt")), 0);
  const int old_fd = ::open((dir / "crash1_modern.h5").c_str(), O_RDONLY);
  ASSERT_GE(old_fd, 0);
  const auto old_size = fs::file_size(dir / "crash1_modern.h5");
  ASSERT_EQ(wait_exit_status(start_run(deck, dir, dir / "2.txt")), 0);
  struct stat st {};
  ASSERT_EQ(::fstat(old_fd, &st), 0);
  EXPECT_EQ(static_cast<std::uintmax_t>(st.st_size), old_size);  // not truncated in place
  ::close(old_fd);
  expect_intact(dir / "crash1_modern.h5", 2);
}

TEST(RunPaths, JobnameWithAPathSeparatorIsRefused) {
  const fs::path dir = testing::fresh_directory("jobname_path");
  const fs::path deck = fs::path(IMPACTFE_TEST_DECKS) / "modern" / "crash1_modern.inp";
  for (const std::string name : {"../escaped", "sub/name", "..", "a\\b"}) {
    const int status =
        wait_exit_status(start_run(deck, dir / "out", dir / "run.txt", {"-j", name}));
    const std::string err = read_text(dir / "run.txt");
    EXPECT_EQ(status, 1) << name << ": " << err;
    EXPECT_NE(err.find("error: -j: "), std::string::npos) << err;
  }
  EXPECT_FALSE(fs::exists(dir / "escaped.h5"));
  EXPECT_FALSE(fs::exists(dir / "escaped.log"));
  // /FILNAME in the deck: refused with the deck's location.
  write_text(dir / "filname.inp", "/FILNAME,../escaped\n/PREP7\nFINISH\n");
  const int status = wait_exit_status(start_run(dir / "filname.inp", dir / "out", dir / "f.txt"));
  const std::string err = read_text(dir / "f.txt");
  EXPECT_EQ(status, 1) << err;
  EXPECT_NE(err.find("filname.inp:1: /FILNAME: jobname '../escaped' contains a path separator"),
            std::string::npos)
      << err;
}

TEST(InputBounds, DeckThatInputsItselfIsRefusedAtOnceWithTheChain) {
  const fs::path dir = testing::fresh_directory("self_input");
  write_text(dir / "self.inp", "/PREP7\n/INPUT,self,inp\n/INPUT,self,inp\n/INPUT,self,inp\n");
  write_text(dir / "a.inp", "/PREP7\n/INPUT,b,inp\n");
  write_text(dir / "b.inp", "N,1\n/INPUT,a,inp\n");
  const auto start = std::chrono::steady_clock::now();
  const int status = wait_exit_status(start_run(dir / "self.inp", dir / "out", dir / "s.txt"));
  const double seconds =
      std::chrono::duration<double>(std::chrono::steady_clock::now() - start).count();
  std::cout << "self-included deck refused in " << seconds << " s\n";
  const std::string err = read_text(dir / "s.txt");
  EXPECT_EQ(status, 1) << err;
  EXPECT_LT(seconds, 2.0);  // was a hang: 3^20 reads in dialect detection
  EXPECT_NE(err.find("self.inp:2: /INPUT: recursive call refused"), std::string::npos) << err;
  ASSERT_EQ(wait_exit_status(start_run(dir / "a.inp", dir / "out", dir / "a.txt")), 1);
  const std::string chain = read_text(dir / "a.txt");
  const std::string a = fs::weakly_canonical(dir / "a.inp").string();
  const std::string b = fs::weakly_canonical(dir / "b.inp").string();
  EXPECT_NE(chain.find("b.inp:2: /INPUT: recursive call refused: file " + a +
                       " is already running (file " + a + " -> file " + b + " -> file " + a + ")"),
            std::string::npos)
      << chain;
}

TEST(InputBounds, DeckWithoutLineEndsIsRefusedWithoutReadingItAll) {
  const fs::path dir = testing::fresh_directory("dev_zero");
  const auto start = std::chrono::steady_clock::now();
  const int status = wait_exit_status(start_run("/dev/zero", dir / "out", dir / "z.txt"));
  const double seconds =
      std::chrono::duration<double>(std::chrono::steady_clock::now() - start).count();
  const std::string err = read_text(dir / "z.txt");
  EXPECT_EQ(status, 1) << err;
  EXPECT_NE(err.find("/dev/zero:1: (line): line longer than 1048576 bytes refused"),
            std::string::npos)
      << err;
  EXPECT_EQ(err.find("bad_alloc"), std::string::npos) << err;
  EXPECT_LT(seconds, 2.0);
  // The same for an /INPUT file and a *LIST: located at the file's line.
  write_text(dir / "inp.inp", "/PREP7\n/INPUT,/dev/zero\n");
  EXPECT_EQ(wait_exit_status(start_run(dir / "inp.inp", dir / "out", dir / "i.txt")), 1);
  EXPECT_NE(read_text(dir / "i.txt").find("/dev/zero:1: (line): line longer than"),
            std::string::npos)
      << read_text(dir / "i.txt");
}

TEST(InputBounds, ReadLimitsCountLinesAndBytes) {
  const fs::path dir = testing::fresh_directory("read_limits");
  write_text(dir / "f.txt", "ab\ncdef\ng\n");
  EXPECT_EQ(*read_file((dir / "f.txt").string(), {100, 4}), "ab\ncdef\ng\n");
  try {
    read_file((dir / "f.txt").string(), {100, 3});
    ADD_FAILURE() << "a line of 4 bytes passed a bound of 3";
  } catch (const OversizedFileError& e) {
    EXPECT_EQ(e.line(), 2);
  }
  try {
    read_file((dir / "f.txt").string(), {9, 0});
    ADD_FAILURE() << "10 bytes passed a bound of 9";
  } catch (const OversizedFileError& e) {
    EXPECT_EQ(e.line(), 0);
  }
}

/// A cube meshed into n³ SOLID185 bricks, fixed at its base, pulled at its top.
std::string cube_deck(int n) {
  return fmt::format(
      "/PREP7\nET,1,SOLID185\nMP,EX,1,200E9\nMP,NUXY,1,0.3\nBLOCK,0,1,0,1,0,1\nESIZE,1/{}\n"
      "VMESH,ALL\nNSEL,S,LOC,Z,0\nD,ALL,ALL\nALLSEL\nNSEL,S,LOC,Z,1\nF,ALL,FZ,1\nALLSEL\n"
      "FINISH\n/SOLU\nANTYPE,STATIC\nSOLVE\nFINISH\n",
      n);
}

TEST(MemoryLimits, MillionsOfBricksAreRefusedAtTheMeshCommandInAnInstant) {
  const fs::path dir = testing::fresh_directory("memory_mesh");
  for (int n : {100, 200}) {  // 1.03 and 8.1 million nodes
    const fs::path deck = dir / fmt::format("cube{}.inp", n);
    write_text(deck, cube_deck(n));
    const auto start = std::chrono::steady_clock::now();
    const int status =
        wait_exit_status(start_run(deck, dir / "out", dir / "m.txt", {"--memory", "8G"}));
    const double seconds =
        std::chrono::duration<double>(std::chrono::steady_clock::now() - start).count();
    const std::string err = read_text(dir / "m.txt");
    std::cout << n << "^3 bricks refused in " << seconds << " s: " << err;
    EXPECT_EQ(status, 1) << err;
    EXPECT_NE(err.find(":7: VMESH: meshing volume 1"), std::string::npos) << err;
    EXPECT_NE(err.find("more than the"), std::string::npos) << err;
    EXPECT_NE(err.find("(--memory 8 GB)"), std::string::npos) << err;
    EXPECT_NE(err.find("elements of this kind would fit"), std::string::npos) << err;
    EXPECT_LT(seconds, 5.0);
  }
  // A mesh that fits is meshed and solved.
  write_text(dir / "small.inp", cube_deck(4));
  EXPECT_EQ(wait_exit_status(
                start_run(dir / "small.inp", dir / "out", dir / "s.txt", {"--memory", "8G"})),
            0)
      << read_text(dir / "s.txt");
  EXPECT_EQ(wait_exit_status(
                start_run(dir / "small.inp", dir / "out", dir / "s.txt", {"--memory", "lots"})),
            1);
}

// An explicit model factors nothing: a million SOLID164 bricks need their element states and
// DOF vectors and a block of stored points (3 GB), not the 30 GB factor that the same SOLID185 mesh
// would need; the mesh-time check refused them as if they were implicit.
TEST(MemoryLimits, ExplicitModelsAreEstimatedWithoutAFactor) {
  for (const char* name : {"SOLID164", "SOLID185"}) {
    Model model;
    model.element_types[1] = ElementType{1, name, {}, {}};
    const ModelMemory m = estimate_model_memory(model, 1, 1.0e6, 1.0e6);
    if (std::string(name) == "SOLID164") {
      EXPECT_EQ(m.factor, 0.0);
      EXPECT_LT(m.total(), 4.0e9) << m.describe();  // the results block: 1.5 GB
    } else {
      EXPECT_GT(m.factor, 1.0e10) << m.describe();
    }
  }
}

TEST(MemoryLimits, SymbolicAnalysisRefusesAFactorThatCannotFit) {
  // A 5-point Laplacian on a 200 x 200 grid: nnz(L) of about 1.5 million (14 MB), with room for
  // 1 MB more than the process holds.
  const int m = 200, n = m * m;
  std::vector<Eigen::Triplet<double>> entries;
  for (int i = 0; i < m; ++i)
    for (int j = 0; j < m; ++j) {
      const int k = i * m + j;
      entries.emplace_back(k, k, 4.0);
      if (i + 1 < m) entries.emplace_back(k + m, k, -1.0);
      if (j + 1 < m) entries.emplace_back(k + 1, k, -1.0);
    }
  SparseMatrix lower(n, n);
  lower.setFromTriplets(entries.begin(), entries.end());
  auto solver = make_linear_solver(n);
  std::ifstream statm("/proc/self/statm");
  double pages = 0.0, resident = 0.0;
  statm >> pages >> resident;
  set_memory_limit(resident * static_cast<double>(::sysconf(_SC_PAGESIZE)) + 1e6);
  try {
    solver->analyze_pattern(lower);
    ADD_FAILURE() << "the factor was not refused";
  } catch (const MemoryLimitError& e) {
    EXPECT_NE(std::string(e.what()).find("the factor of the 40000 equations (nnz(L) = "),
              std::string::npos)
        << e.what();
  }
  set_memory_limit(std::nullopt);
  EXPECT_NO_THROW(solver->analyze_pattern(lower));
}

/// Resident memory of this process (bytes), from /proc/self/statm.
double resident_bytes_now() {
  std::ifstream statm("/proc/self/statm");
  double pages_total = 0.0, pages_resident = 0.0;
  statm >> pages_total >> pages_resident;
  return pages_resident * static_cast<double>(sysconf(_SC_PAGESIZE));
}

TEST(MemoryLimits, ReducedTransientHistoryGoesToAFileUnderATightLimitWithTheSameResults) {
  // The car crash (reduced, modern form) in steps of 1 µs: 6,001 points, a 1 MB history. With
  // 32 MB left to the run (room for a sanitizer build), the history's block is at most 512 kB
  // and the rest goes to the temporary file; the expansion pass (NUMEXP,ALL) reads every point
  // back and gives the same results as the run that kept it all in memory. (Before, the
  // history was held in memory whole, and a run whose history did not fit was refused.)
  std::string deck = read_text(fs::path(IMPACTFE_TEST_DECKS) / "modern" / "crash1_modern.inp");
  for (const auto& [from, to] : {std::pair<std::string, std::string>{"DELTIM,1E-4", "DELTIM,1E-6"},
                                 {"TIME,1E-4", "TIME,1E-6"}}) {
    const auto pos = deck.find(from);
    ASSERT_NE(pos, std::string::npos) << from;
    deck.replace(pos, from.size(), to);
  }
  const auto in_memory = testing::run_deck_text("history_in_memory", deck);
  set_memory_limit(resident_bytes_now() + 32e6);
  std::unique_ptr<testing::DeckRun> on_file;
  try {
    on_file = std::make_unique<testing::DeckRun>(testing::run_deck_text("history_on_file", deck));
  } catch (...) {
    set_memory_limit(std::nullopt);
    throw;
  }
  set_memory_limit(std::nullopt);
  auto noted = [](const testing::DeckRun& run) {
    for (const auto& a : run.statistics.analyses)
      for (const auto& note : a.notes)
        if (note.find("state history:") != std::string::npos) return true;
    return false;
  };
  EXPECT_FALSE(noted(in_memory));
  EXPECT_TRUE(noted(*on_file));
  const auto a = in_memory.reader->analyses();
  const auto b = on_file->reader->analyses();
  ASSERT_EQ(a.size(), b.size());
  ASSERT_GE(a.size(), 2u);
  const auto& expansion = a.back();
  // Bitwise, NaN (a DOF the element set lacks) equal to NaN.
  auto same = [](const auto& x, const auto& y) {
    return x.rows() == y.rows() && x.cols() == y.cols() &&
           (x.array() == y.array() || (x.array().isNaN() && y.array().isNaN())).all();
  };
  ASSERT_EQ(expansion.n_time_points, 6001);
  ASSERT_EQ(b.back().n_time_points, 6001);
  for (int k : {0, 1, 2999, 5999, 6000}) {
    const TimePoint x = in_memory.reader->time_point(expansion.index, k);
    const TimePoint y = on_file->reader->time_point(expansion.index, k);
    EXPECT_EQ(x.time, y.time) << k;
    EXPECT_TRUE(same(x.displacement, y.displacement)) << k;
    EXPECT_TRUE(same(x.acceleration, y.acceleration)) << k;
    EXPECT_TRUE(same(x.gap_forces, y.gap_forces)) << k;
  }
}

}  // namespace
}  // namespace impactfe::test_run_safety
