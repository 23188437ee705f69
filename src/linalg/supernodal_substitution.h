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

}  // namespace impactfe
