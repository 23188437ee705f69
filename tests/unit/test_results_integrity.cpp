// Integrity of the results file (issue 12): corrupted bytes anywhere in a results file are either
// harmless (unused space: everything reads back as written) or reported; never different numbers
// without an error. A small file with every kind of dataset (tests/decks/integrity) is corrupted
// region by region (8 random bytes each), and what `impactfe info`, `post` and `export` compute
// from it (results_info, post_csv of every node, DOF, element item and gap, the VTU export) is
// compared with what they compute from the intact file, in a child process per copy so that a
// crash is seen as one.
//
// Regions: a dense random sample by default (IMPACTFE_CORRUPTION_TRIALS, default 150);
// IMPACTFE_CORRUPTION_STRIDE=N corrupts every N-th offset of the whole file instead (N = 8: every
// byte of the file in some region; about 13,000 copies, a few minutes).
#include <gtest/gtest.h>
#include <sys/wait.h>
#include <unistd.h>

#include <cstdlib>
#include <fstream>
#include <random>
#include <sstream>

#include "../support/run_deck.h"
#include "results/post_csv.h"
#include "results/vtk_export.h"

namespace impactfe::test_results_integrity {
namespace {

namespace fs = std::filesystem;

std::string read_bytes(const fs::path& path) {
  std::ifstream in(path, std::ios::binary);
  std::stringstream s;
  s << in.rdbuf();
  return s.str();
}

/// Every post request of the file's nodes, DOF labels, element items and gaps that the intact
/// file answers (an item an element does not have is an error of the request).
std::vector<PostRequest> valid_requests(const std::string& path) {
  ResultsReader reader(path);
  std::vector<PostRequest> all, valid;
  for (int node : reader.node_ids())
    for (const char* lab : {"UX", "UY", "UZ", "VX", "AX", "FX", "FY"})
      all.push_back(parse_nsol(std::to_string(node) + "," + lab));
  for (const auto& e : reader.elements())
    for (const char* item : {"FORC", "SAXL", "STAT", "F1", "STRETCH"})
      all.push_back(parse_esol(std::to_string(e.id) + "," + item));
  all.push_back(parse_gapf("1"));
  for (const auto& request : all) {
    try {
      post_csv(reader, {request});
      valid.push_back(request);
    } catch (const InputError&) {
    }
  }
  return valid;
}

/// Everything info, post and export give for the file at `path`, as one text (the file's own
/// path replaced, so that copies compare equal). Any InputError is what the CLI reports.
std::string everything(const std::string& path, const fs::path& export_dir,
                       const std::vector<PostRequest>& requests) {
  ResultsReader reader(path);
  std::string out = results_info(reader);
  for (auto pos = out.find(path); pos != std::string::npos; pos = out.find(path))
    out.replace(pos, path.size(), "FILE");
  out += post_csv(reader, requests);
  out += frequencies_csv(reader);
  out += mode_shape_csv(reader, 2);
  fs::remove_all(export_dir);
  fs::create_directories(export_dir);
  const ExportSummary s = export_vtu_series(reader, export_dir.string(), "x");
  for (const auto& file : s.files) out += read_bytes(file);
  return out;
}

void overwrite(const fs::path& path, long long at, const std::string& bytes) {
  std::fstream f(path, std::ios::in | std::ios::out | std::ios::binary);
  f.seekp(at);
  f.write(bytes.data(), static_cast<std::streamsize>(bytes.size()));
}

long long env_number(const char* name, long long fallback) {
  const char* v = std::getenv(name);
  return v != nullptr && *v != '\0' ? std::atoll(v) : fallback;
}

TEST(ResultsIntegrity, CorruptionAnywhereIsReportedOrHarmless) {
  const fs::path dir = testing::fresh_directory("integrity");
  const std::string deck =
      (fs::path(IMPACTFE_TEST_DECKS) / "integrity" / "small_results.inp").string();
  const std::string path = testing::run_deck_in(deck, dir).results_path;
  const fs::path copy_dir = dir / "copy";
  fs::create_directories(copy_dir);
  const fs::path copy = copy_dir / "small_results.h5";
  fs::copy_file(path, copy);
  const std::vector<PostRequest> requests = valid_requests(copy.string());
  ASSERT_GT(requests.size(), 20u);
  const std::string reference = everything(copy.string(), dir / "export", requests);
  ASSERT_NE(reference.find("Analysis 2: transient"), std::string::npos) << reference;
  const std::string original = read_bytes(path);
  const auto size = static_cast<long long>(original.size());

  std::vector<long long> offsets;
  std::mt19937 rng(20261123);
  if (const long long stride = env_number("IMPACTFE_CORRUPTION_STRIDE", 0); stride > 0) {
    for (long long at = 0; at + 8 <= size; at += stride) offsets.push_back(at);
  } else {
    const long long trials = env_number("IMPACTFE_CORRUPTION_TRIALS", 150);
    for (long long t = 0; t < trials; ++t)
      offsets.push_back(std::uniform_int_distribution<long long>(0, size - 8)(rng));
  }
  int reported = 0, harmless = 0;
  std::vector<std::string> failures;
  for (long long at : offsets) {
    std::string bytes(8, '\0');
    for (auto& b : bytes) b = static_cast<char>(rng());
    if (original.compare(static_cast<std::size_t>(at), 8, bytes) == 0) continue;
    fs::copy_file(path, copy, fs::copy_options::overwrite_existing);
    overwrite(copy, at, bytes);
    const pid_t pid = fork();
    ASSERT_GE(pid, 0);
    if (pid == 0) {
      alarm(30);
      int code = 3;
      try {
        code = everything(copy.string(), dir / "export_copy", requests) == reference ? 0 : 2;
      } catch (const InputError&) {
        code = 1;  // what the CLI reports with exit status 1
      } catch (...) {
        code = 4;
      }
      _exit(code);
    }
    int status = 0;
    waitpid(pid, &status, 0);
    const int code = WIFEXITED(status) ? WEXITSTATUS(status) : 128 + WTERMSIG(status);
    if (code == 0) ++harmless;
    if (code == 1) ++reported;
    if (code == 2) failures.push_back(std::to_string(at) + ": different values, no error");
    if (code == 4) failures.push_back(std::to_string(at) + ": an error that is not an InputError");
    if (code > 4)
      failures.push_back(std::to_string(at) + ": crash (status " + std::to_string(code) + ")");
  }
  std::cout << offsets.size() << " corrupted copies of a " << size << "-byte file: " << reported
            << " reported, " << harmless << " harmless, " << failures.size() << " failures\n";
  for (std::size_t i = 0; i < failures.size() && i < 40; ++i)
    ADD_FAILURE() << "8 bytes overwritten at offset " << failures[i];
  EXPECT_TRUE(failures.empty());
  EXPECT_GT(reported, static_cast<int>(offsets.size()) / 10);
}

}  // namespace
}  // namespace impactfe::test_results_integrity
