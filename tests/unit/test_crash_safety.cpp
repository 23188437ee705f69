// Crash safety of the results file (issue 12): a run killed with SIGKILL half-way through an
// expansion pass or a superelement expansion pass keeps every completed step readable (the
// same for a full transient is ResultsFileTest.KilledRunKeepsAppendedPoints), and a full disk
// or an unwritable output directory ends the run with a clear message and exit status 2, the
// results written so far staying readable.
#include <fcntl.h>
#include <gtest/gtest.h>
#include <signal.h>
#include <sys/mount.h>
#include <sys/resource.h>
#include <sys/wait.h>
#include <unistd.h>

#include <chrono>
#include <cmath>
#include <fstream>
#include <sstream>
#include <thread>

#include "../support/run_deck.h"

namespace impactfe::test_crash_safety {
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

/// `impactfe run DECK -o DIR` in a child process, stderr to DIR/../<stem>.stderr. `file_limit`
/// > 0: RLIMIT_FSIZE in bytes (a write past it fails with EFBIG, SIGXFSZ ignored), the portable
/// stand-in for a full disk.
pid_t start_run(const fs::path& deck, const fs::path& dir, const fs::path& stderr_file,
                rlim_t file_limit = 0, const std::string& results_thread = "auto") {
  const pid_t pid = fork();
  if (pid != 0) return pid;
  const int fd = ::open(stderr_file.c_str(), O_WRONLY | O_CREAT | O_TRUNC, 0644);
  if (fd >= 0) {
    dup2(fd, 2);
    dup2(fd, 1);
  }
  if (file_limit > 0) {
    signal(SIGXFSZ, SIG_IGN);
    rlimit limit{file_limit, file_limit};
    setrlimit(RLIMIT_FSIZE, &limit);
  }
  execl(IMPACTFE_BINARY, IMPACTFE_BINARY, "run", deck.c_str(), "-o", dir.c_str(),
        "--results-thread", results_thread.c_str(), static_cast<char*>(nullptr));
  _exit(127);
}

int wait_exit_status(pid_t pid) {
  int status = 0;
  waitpid(pid, &status, 0);
  if (WIFSIGNALED(status)) return 128 + WTERMSIG(status);
  return WEXITSTATUS(status);
}

/// Stored points of analysis `a` of a results file being written, or -1 when the file cannot
/// be read yet.
int points_of(const fs::path& results, int a) {
  try {
    ResultsReader reader(results.string());
    const auto analyses = reader.analyses();
    if (static_cast<int>(analyses.size()) < a) return 0;
    return analyses[static_cast<std::size_t>(a - 1)].n_time_points;
  } catch (const std::exception&) {
    return -1;
  }
}

/// Starts the run of `deck` in `dir`, waits until analysis `a` has stored `points` time points,
/// and kills it with SIGKILL. Fails when the run ends before (the deck is not long enough).
void kill_half_way(const fs::path& deck, const fs::path& dir, int a, int points) {
  const fs::path results = dir / (deck.stem().string() + ".h5");
  const pid_t pid = start_run(deck, dir, dir / "run.stderr");
  const auto deadline = std::chrono::steady_clock::now() + std::chrono::seconds(300);
  bool reached = false;
  while (std::chrono::steady_clock::now() < deadline) {
    int status = 0;
    if (waitpid(pid, &status, WNOHANG) == pid) {
      FAIL() << "the run ended before it was killed: " << read_text(dir / "run.stderr");
    }
    if (fs::exists(results) && points_of(results, a) >= points) {
      reached = true;
      break;
    }
    std::this_thread::sleep_for(std::chrono::milliseconds(20));
  }
  kill(pid, SIGKILL);
  int status = 0;
  waitpid(pid, &status, 0);
  ASSERT_TRUE(reached) << "analysis " << a << " did not reach " << points << " points";
  ASSERT_TRUE(WIFSIGNALED(status)) << "the run was not killed";
}

/// Every stored point of analysis `a` of `killed` reads back and equals the same point of the
/// complete run `complete` (same time, same displacements).
void expect_completed_points_readable(const fs::path& killed, const fs::path& complete, int a) {
  ResultsReader k(killed.string());
  ResultsReader c(complete.string());
  const auto info = k.analyses().at(static_cast<std::size_t>(a - 1));
  EXPECT_EQ(info.status, "running");  // killed: the status was never closed
  const int n = info.n_time_points;
  ASSERT_GT(n, 0);
  ASSERT_LT(n, c.analyses().at(static_cast<std::size_t>(a - 1)).n_time_points)
      << "the run was killed after it finished";
  for (int i = 0; i < n; ++i) {
    const TimePoint pk = k.time_point(a, i);
    const TimePoint pc = c.time_point(a, i);
    ASSERT_EQ(pk.time, pc.time) << "point " << i;
    ASSERT_EQ(pk.displacement.rows(), pc.displacement.rows());
    for (Eigen::Index r = 0; r < pk.displacement.rows(); ++r)
      for (Eigen::Index col = 0; col < 6; ++col) {
        const double x = pk.displacement(r, col), y = pc.displacement(r, col);
        ASSERT_TRUE((std::isnan(x) && std::isnan(y)) || x == y)
            << "point " << i << " row " << r << " col " << col << ": " << x << " vs " << y;
      }
  }
}

/// The car crash (case 1, modern form) with a long reduced transient and an expansion at every
/// step: the expansion pass (analysis 2) writes one point per step.
std::string long_expansion_deck() {
  std::string deck = read_text(fs::path(IMPACTFE_TEST_DECKS) / "modern" / "crash1_modern.inp");
  const auto replace = [&deck](const std::string& from, const std::string& to) {
    const auto pos = deck.find(from);
    if (pos != std::string::npos) deck.replace(pos, from.size(), to);
  };
  replace("DELTIM,1E-4", "DELTIM,1E-6");
  replace("TIME,1E-4", "TIME,1E-6");
  replace("TIME,0.006", "TIME,0.02");
  return deck;
}

TEST(CrashSafety, KilledExpansionPassKeepsCompletedSteps) {
  const fs::path dir = testing::fresh_directory("crash_expansion");
  const fs::path deck = dir / "expansion.inp";
  write_text(deck, long_expansion_deck());
  // The complete run, for reference.
  fs::create_directories(dir / "complete");
  ASSERT_EQ(wait_exit_status(start_run(deck, dir / "complete", dir / "complete.stderr")), 0)
      << read_text(dir / "complete.stderr");
  fs::create_directories(dir / "killed");
  kill_half_way(deck, dir / "killed", 2, 200);
  expect_completed_points_readable(dir / "killed" / "expansion.h5",
                                   dir / "complete" / "expansion.h5", 2);
}

TEST(CrashSafety, KilledSuperelementExpansionKeepsCompletedSteps) {
  const fs::path dir = testing::fresh_directory("crash_superelement");
  const std::string decks = IMPACTFE_TEST_DECKS;
  // Generation and a long transient use pass (the bar superelement hit by a force pulse).
  testing::run_deck_in(decks + "/modern/se_generate_bar.inp", dir);
  write_text(
      dir / "use.inp",
      "/PREP7\nET,1,MATRIX50\nET,2,COMBIN14,,1\nR,2,1000\nN,1,0\nN,11,10\nN,12,11\n"
      "TYPE,1\nSE,bar\nTYPE,2\nREAL,2\nE,11,12\nFINISH\n/SOLU\nANTYPE,TRANS\n"
      "TRNOPT,FULL\nOUTRES,ALL,ALL\nD,1,UX\nD,12,UX\nF,11,FX,1000\nTIME,1E-5\nDELTIM,1E-5\nSOLVE\n"
      "FDELE,ALL,ALL\nTIME,0.02\nSOLVE\nFINISH\n");
  testing::run_deck_in((dir / "use.inp").string(), dir);
  write_text(dir / "seexp.inp", "/SOLU\nEXPASS,ON\nSEEXP,bar,use\nNUMEXP,ALL\nSOLVE\nFINISH\n");
  // Expansion decks run in the directory of the generation and use passes.
  const auto run_expansion = [&](const std::string& sub) {
    fs::create_directories(dir / sub);
    for (const char* f : {"bar.sub.h5", "use.h5"}) fs::copy_file(dir / f, dir / sub / f);
    fs::copy_file(dir / "seexp.inp", dir / sub / "seexp.inp");
    return dir / sub / "seexp.inp";
  };
  const fs::path complete = run_expansion("complete");
  ASSERT_EQ(wait_exit_status(start_run(complete, dir / "complete", dir / "complete.stderr")), 0)
      << read_text(dir / "complete.stderr");
  const fs::path killed = run_expansion("killed");
  kill_half_way(killed, dir / "killed", 1, 200);
  expect_completed_points_readable(dir / "killed" / "seexp.h5", dir / "complete" / "seexp.h5", 1);
}

/// Runs the helmet (190 stored steps, about 80 kB of results per step) into `dir`; `limit` > 0
/// limits the size of every file the run writes. `results_thread`: --results-thread.
int run_helmet(const fs::path& dir, rlim_t limit, std::string& err,
               const std::string& results_thread = "auto") {
  const fs::path deck = fs::path(IMPACTFE_TEST_DECKS) / "thesis" / "helmet_full.inp";
  const int status =
      wait_exit_status(start_run(deck, dir, dir.string() + ".stderr", limit, results_thread));
  err = read_text(dir.string() + ".stderr");
  return status;
}

/// The results a run wrote before the disk filled: the analysis is there, every stored point
/// reads back with finite displacements where the model has DOFs.
void expect_partial_results_readable(const fs::path& results) {
  ResultsReader r(results.string());
  const auto analyses = r.analyses();
  ASSERT_EQ(analyses.size(), 1u);
  const int n = analyses[0].n_time_points;
  EXPECT_GT(n, 0);
  EXPECT_LT(n, 191);
  const auto times = r.times(1);
  ASSERT_EQ(static_cast<int>(times.size()), n);
  for (int i = 0; i < n; ++i) {
    const TimePoint p = r.time_point(1, i);
    EXPECT_EQ(p.time, times[static_cast<std::size_t>(i)]);
    EXPECT_TRUE(std::isfinite(p.displacement(0, 2)));  // node 1 UZ
  }
  EXPECT_FALSE(r.nodal_series(43, "UZ").empty());
}

TEST(CrashSafety, FileSizeLimitEndsWithExitTwoAndAClearMessage) {
  // RLIMIT_FSIZE: a write past 150 kB fails (EFBIG) as on a full disk, in any sandbox.
  const fs::path dir = testing::fresh_directory("full_disk") / "out";
  fs::create_directories(dir);
  std::string err;
  const int status = run_helmet(dir, 150 * 1024, err);
  EXPECT_EQ(status, 2) << err;
  EXPECT_NE(err.find("error: "), std::string::npos) << err;
  EXPECT_NE(err.find("helmet_full.h5"), std::string::npos) << err;
  EXPECT_NE(err.find("File too large"), std::string::npos) << err;
  EXPECT_NE(err.find("results up to the failure are kept"), std::string::npos) << err;
}

// A write past the limit fails half-way through the run: the writer reserves the space of
// every write first (h5::reserve_space), so the failure comes before HDF5 touches the file and
// every point flushed before it reads back (before the reservation, HDF5 had already rewritten
// the superblock with the new end of file, and the file was refused as truncated). The limits
// take the first block (64 points, 1.9 MB, twice that reserved: the run keeps 64 points at
// 4.25 and 4.5 MB, 128 at 5 MB), not the whole run's; a run slow enough to sync by time (every
// 0.1 s) keeps more.
// The same with the results written on a thread of their own or on the solver's
// (--results-thread): the failure comes back from the writer thread at a later call.
TEST(CrashSafety, FileSizeLimitKeepsResultsReadable) {
  for (const char* thread : {"on", "off"})
    for (rlim_t limit : {4352 * 1024, 4608 * 1024, 5120 * 1024}) {
      const fs::path dir =
          testing::fresh_directory("file_size_limit_" + std::to_string(limit) + "_" + thread) /
          "out";
      fs::create_directories(dir);
      std::string err;
      ASSERT_EQ(run_helmet(dir, limit, err, thread), 2) << thread << "\n" << err;
      EXPECT_NE(err.find("File too large"), std::string::npos) << err;
      EXPECT_NE(err.find("results up to the failure are kept"), std::string::npos) << err;
      expect_partial_results_readable(dir / "helmet_full.h5");
    }
}

/// Mounts a tmpfs of `size` at `dir` (root with CAP_SYS_ADMIN only); false when not allowed.
bool mount_tmpfs(const fs::path& dir, const std::string& options) {
  fs::create_directories(dir);
  return ::mount("tmpfs", dir.c_str(), "tmpfs", 0, options.c_str()) == 0;
}

TEST(CrashSafety, FullTmpfsEndsWithExitTwoAndKeepsResults) {
  const fs::path dir = testing::fresh_directory("full_tmpfs") / "mnt";
  if (!mount_tmpfs(dir, "size=4m"))  // the first block fits (FileSizeLimitKeepsResultsReadable)
    GTEST_SKIP() << "mounting a tmpfs is not permitted here (RLIMIT_FSIZE test covers it)";
  std::string err;
  const int status = run_helmet(dir, 0, err);
  const bool ok = status == 2 && err.find("No space left on device") != std::string::npos;
  if (ok) expect_partial_results_readable(dir / "helmet_full.h5");
  umount(dir.c_str());
  EXPECT_TRUE(ok) << "exit status " << status << "\n" << err;
}

TEST(CrashSafety, OutputDirectoryThatIsAFileEndsWithExitTwo) {
  const fs::path dir = testing::fresh_directory("unwritable");
  write_text(dir / "plain_file", "x");
  // stderr goes next to the plain file (no file can be created under it).
  const fs::path deck = fs::path(IMPACTFE_TEST_DECKS) / "thesis" / "helmet_full.inp";
  const int status =
      wait_exit_status(start_run(deck, dir / "plain_file" / "out", dir / "run.stderr"));
  const std::string err = read_text(dir / "run.stderr");
  EXPECT_EQ(status, 2) << err;
  EXPECT_NE(err.find("cannot use the output directory"), std::string::npos) << err;
  EXPECT_NE(err.find("Not a directory"), std::string::npos) << err;
}

TEST(CrashSafety, ReadOnlyOutputDirectoryEndsWithExitTwo) {
  const fs::path dir = testing::fresh_directory("read_only") / "ro";
  bool mounted = false;
  if (geteuid() == 0) {
    // Root writes through permission bits: a read-only tmpfs is the unwritable directory.
    mounted = mount_tmpfs(dir, "size=64k,mode=0755");
    if (mounted)
      mounted = ::mount("tmpfs", dir.c_str(), "tmpfs", MS_REMOUNT | MS_RDONLY, "size=64k") == 0;
    if (!mounted) GTEST_SKIP() << "root without mount permission: no unwritable directory";
  } else {
    fs::create_directories(dir);
    fs::permissions(dir, fs::perms::owner_read | fs::perms::owner_exec);
  }
  std::string err;
  const int status = run_helmet(dir, 0, err);
  if (mounted) umount(dir.c_str());
  EXPECT_EQ(status, 2) << err;
  EXPECT_NE(err.find("cannot write in the output directory"), std::string::npos) << err;
  EXPECT_TRUE(err.find("Read-only file system") != std::string::npos ||
              err.find("Permission denied") != std::string::npos)
      << err;
}

}  // namespace
}  // namespace impactfe::test_crash_safety
