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
/// of a finite-element factor are small, so that costs about twice the floor (issue 11,
/// docs/benchmarks.md). Here each supernode is one pass over its values, column by column in
/// storage order, four columns at a time so that the rows below the diagonal block are read
/// once per four columns of the right-hand side (George & Liu 1981 §6; Davis 2006 §4.2).
#include <vector>

namespace impactfe {

struct SupernodalLayout {
  int n_super = 0;
  const int* super = nullptr;        // n_super + 1 column starts
  const int* row_start = nullptr;    // n_super + 1 starts in rows
  const int* value_start = nullptr;  // n_super + 1 starts in values
  const int* rows = nullptr;
  const double* values = nullptr;
};

/// y ← L⁻¹ y, in the factor's (permuted) order. `work` is scratch (resized as needed).
void forward_substitution(const SupernodalLayout& factor, double* y, std::vector<double>& work);
/// y ← L⁻ᵀ y, in the factor's (permuted) order.
void back_substitution(const SupernodalLayout& factor, double* y, std::vector<double>& work);
/// The longest run of rows below a supernode's diagonal block (the size `work` needs).
int largest_update(const SupernodalLayout& factor);

}  // namespace impactfe
