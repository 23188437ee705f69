#pragma once
/// The state history of a reduced / mode-superposition transient (q, q̇, q̈ and the GP gap
/// forces at every computed point), kept for the expansion pass in bounded memory: points are
/// gathered in a block of at most `block_bytes`; each full block goes to an anonymous temporary
/// file (removed when the run ends), as MAPDL keeps these histories in its .rdsp file. Reading
/// a point takes it from the block in memory or reads its record back from the file.
#include <cstddef>
#include <cstdio>
#include <memory>
#include <string>
#include <vector>

#include "linalg/sparse.h"

namespace impactfe {

class GeneralizedHistory {
 public:
  /// The block a run keeps in memory: a 64th of the memory the run may still take
  /// (memory_budget.h: the machine, the cgroup, `--memory`), between 64 kB and 32 MB.
  static std::size_t default_block_bytes();

  struct Record {
    VectorXd q, v, a, gap_forces;
  };

  GeneralizedHistory(int n_coordinates, int n_gaps,
                     std::size_t block_bytes = default_block_bytes());

  /// Bytes one point takes on file (and in the block).
  static double bytes_per_point(int n_coordinates, int n_gaps);
  /// Refuses (MemoryLimitError: the disk is the memory here) a history of `n_points` that does
  /// not fit in the free space of the temporary directory, saying how many points would.
  static void require_disk_space(double n_points, int n_coordinates, int n_gaps);

  void append(const VectorXd& q, const VectorXd& v, const VectorXd& a, const VectorXd& gap_forces);
  std::size_t size() const { return n_on_file_ + n_in_block_; }
  Record at(std::size_t k) const;
  /// The points written to the temporary file so far (for tests and the run summary).
  std::size_t points_on_file() const { return n_on_file_; }

 private:
  void flush_block();

  int nq_ = 0, ng_ = 0;
  std::size_t record_ = 0;        // doubles per point: 3 nq + ng
  std::size_t block_points_ = 1;  // points per block
  std::vector<double> block_;
  std::size_t n_in_block_ = 0, n_on_file_ = 0;
  struct FileCloser {
    void operator()(std::FILE* f) const { std::fclose(f); }
  };
  std::unique_ptr<std::FILE, FileCloser> file_;
};

}  // namespace impactfe
