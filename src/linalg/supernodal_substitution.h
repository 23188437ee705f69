#pragma once
/// Forward and back substitution with a supernodal Cholesky factor L (P A Pᵀ = L Lᵀ) stored the
/// way CHOLMOD stores it: supernode s owns columns super[s] .. super[s + 1] − 1, its row indices
/// are rows[row_start[s] ...] (its own columns first, then the rows below), its values a dense
/// column-major block of those rows × its columns at values[value_start[s] ...].
///
/// A transient's step is one solve with a factor that does not fit in the caches, so the solve
/// is bounded by the memory bandwidth: it cannot take less than 2 × bytes(L) / bandwidth (L is
/// read once forward and once backward). CHOLMOD's supernodal solve makes a dtrsv and a dgemv
/// call per supernode, through a gathered workspace copy of the right-hand side; most supernodes
/// of a finite-element factor are small, so that costs 4–5 times the floor on a shell factor
/// (docs/benchmarks.md). Here each supernode is one pass over its values in storage order,
/// with its rows of the right-hand side gathered side by side: column by column (one sequential
/// stream, which the hardware prefetcher follows), or eight columns at a time where columns are
/// long (George & Liu 1981 §6; Davis 2006 §4.2).
#include <vector>

namespace impactfe {

struct SupernodalLayout {
  int n_super = 0;
  const int* super = nullptr;        // n_super + 1 column starts
  const int* row_start = nullptr;    // n_super + 1 starts in rows
  const int* value_start = nullptr;  // n_super + 1 starts in values
  const int* rows = nullptr;
  const double* values = nullptr;
  /// Supernodes with more rows than this take their columns eight at a time (see the .cpp;
  /// the tests lower it to reach that path with small factors).
  int long_column = 1024;
};

/// y ← L⁻¹ y, in the factor's (permuted) order. `work` is scratch (resized as needed).
void forward_substitution(const SupernodalLayout& factor, double* y, std::vector<double>& work);
/// y ← L⁻ᵀ y, in the factor's (permuted) order.
void back_substitution(const SupernodalLayout& factor, double* y, std::vector<double>& work);

/// The same substitutions on several threads (issue 11). A step of a large transient is one
/// solve bounded by the memory bandwidth, and two cores of this machine stream twice the bytes
/// of one (two BM_SupernodalSolve/160 runs side by side each take the time of one alone).
///
/// Disjoint subtrees of the supernodal elimination tree are independent (George & Liu
/// 1981: a column's rows below are its ancestors): the plan cuts the tree at its top separators
/// into subtrees and packs them into `kGroups` groups of similar weight, which threads take one
/// at a time. The back substitution solves the separators, then the groups side by side: it
/// only reads what is above a subtree, so its results are those of back_substitution, bitwise.
/// The forward substitution runs the groups first: each adds its updates of the separators'
/// rows into a buffer of its own, and the buffers are added to y in group order before the
/// separators are solved. The plan depends on the factor's structure alone, never on the
/// thread count, so the results are the same bits on any number of threads (they differ from
/// forward_substitution's by the order of those additions, at round-off).
class SubtreeSubstitution {
 public:
  /// Factors with fewer values stay on one thread: they fit in the caches, where a solve takes
  /// less than waking a thread.
  static constexpr long long kMinValues = 1LL << 21;
  static constexpr int kGroups = 8;

  SubtreeSubstitution() = default;
  /// Plans for `factor` (again after every factorization; its values may change in between).
  /// Without a plan (a small factor, or a tree with no split) the substitutions are the serial
  /// ones.
  void plan(const SupernodalLayout& factor, long long min_values = kMinValues);
  /// Groups substituted side by side (0: none, the serial substitutions).
  int groups() const { return static_cast<int>(groups_.size()); }
  /// Values of L in the separators, solved on one thread (a fraction of the factor's).
  double serial_fraction() const { return serial_fraction_; }

  void forward(const SupernodalLayout& factor, double* y);
  void back(const SupernodalLayout& factor, double* y);

 private:
  /// The subtrees (`roots`, sorted here) packed into groups; each group's separator rows.
  void pack_groups(const SupernodalLayout& f, const std::vector<long long>& subtree,
                   const std::vector<int>& first, std::vector<int>& roots);
  /// Sorts each group and checks that its subtrees update no row outside themselves but the
  /// separator rows it lists (false: the plan cannot be used).
  bool groups_update_only_separators(const SupernodalLayout& f);
  struct Subtree {
    int first = 0, last = 0;  // its supernodes first..last (postorder: last is its root)
    int end_column = 0;       // its columns end here; every row at or past it is a separator's
  };
  struct Group {
    std::vector<Subtree> subtrees;
    std::vector<int> touched;    // positions of the separator rows its subtrees update
    std::vector<double> update;  // by separator position; zero between substitutions
    std::vector<double> work;
  };
  int n_super_ = 0;
  std::vector<Group> groups_;
  std::vector<int> separators_;          // the supernodes in no subtree, ascending
  std::vector<int> separator_position_;  // per column: its position among the separators' columns
  std::vector<int> separator_column_;    // per position: the column
  std::vector<double> work_;
  double serial_fraction_ = 1.0;
};

}  // namespace impactfe
