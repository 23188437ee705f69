#include "linalg/supernodal_substitution.h"

#include <algorithm>
#include <cstring>

namespace impactfe {

namespace {

/// Two doubles in one register (SSE2 on x86-64, NEON elsewhere): the dot products of the back
/// substitution are reductions, which the compiler does not vectorize without reassociating.
typedef double Pair __attribute__((vector_size(16)));

inline Pair load_pair(const double* p) {
  Pair v;
  std::memcpy(&v, p, sizeof v);
  return v;
}

/// Columns of L per pass over a supernode's rows. One column at a time reads the supernode's
/// values as one sequential stream (its columns are contiguous), which the hardware prefetcher
/// follows best: measured on columns of 12 to 1000 rows, 18-25 GB/s against 7-20 GB/s for
/// passes over 4 or 8 columns side by side. Longer columns (SupernodalLayout::long_column)
/// make the gathered rows of the right-hand side (8 bytes each, loaded and stored per value)
/// leave the L1 cache; there kBlock columns per pass load them once per kBlock values of L (20
/// against 13 GB/s at 4000 rows).
constexpr int kBlock = 8;

struct Supernode {
  int first_column, columns, rows;  // rows: its own columns' rows first, then those below
  const int* row;
  const double* value;  // column-major, leading dimension `rows`
};

inline Supernode supernode(const SupernodalLayout& f, int s) {
  Supernode node;
  node.first_column = f.super[s];
  node.columns = f.super[s + 1] - f.super[s];
  node.rows = f.row_start[s + 1] - f.row_start[s];
  node.row = f.rows + f.row_start[s];
  node.value = f.values + f.value_start[s];
  return node;
}

/// t[i] −= Σ_c column_c[i] · a_c over rows [begin, end) of the W columns (W ≤ kBlock).
template <int W>
inline void subtract_columns(const double* const* column, const double* a, int begin, int end,
                             double* __restrict t) {
  for (int i = begin; i < end; ++i) {
    double sum = column[0][i] * a[0];
    for (int c = 1; c < W; ++c) sum += column[c][i] * a[c];
    t[i] -= sum;
  }
}

/// Calls kernel<W>() for the block width w in 1 .. kBlock (a compile-time width: the column
/// loop unrolls and its pointers stay in registers).
template <template <int> class Kernel, class... Args>
inline void with_width(int w, Args&&... args) {
  switch (w) {
    case 8:
      if constexpr (kBlock >= 8) Kernel<8>::run(args...);
      break;
    case 7:
      if constexpr (kBlock >= 7) Kernel<7>::run(args...);
      break;
    case 6:
      if constexpr (kBlock >= 6) Kernel<6>::run(args...);
      break;
    case 5:
      if constexpr (kBlock >= 5) Kernel<5>::run(args...);
      break;
    case 4:
      if constexpr (kBlock >= 4) Kernel<4>::run(args...);
      break;
    case 3:
      if constexpr (kBlock >= 3) Kernel<3>::run(args...);
      break;
    case 2:
      if constexpr (kBlock >= 2) Kernel<2>::run(args...);
      break;
    default:
      Kernel<1>::run(args...);
      break;
  }
}

template <int W>
struct SubtractColumns {
  static void run(const double* const* column, const double* a, int begin, int end, double* t) {
    subtract_columns<W>(column, a, begin, end, t);
  }
};

/// dot[c] += Σ_i column_c[i] · x[i − begin] over rows [begin, end) of the W columns.
template <int W>
inline void add_dots(const double* const* column, const double* __restrict x, int begin, int end,
                     double* dot) {
  // From the last row to the first, as add_dots<1> below.
  Pair sum[W] = {};
  int i = end;
  for (; i - 2 >= begin;) {
    i -= 2;
    const Pair xi = load_pair(x + (i - begin));
    for (int c = 0; c < W; ++c) sum[c] += load_pair(column[c] + i) * xi;
  }
  for (int c = 0; c < W; ++c) {
    dot[c] += sum[c][0] + sum[c][1];
    if (i > begin) dot[c] += column[c][begin] * x[0];
  }
}

/// One column: read from its last row to its first, because the back substitution visits the
/// columns from the last: the whole pass is then one descending stream (ascending runs within
/// descending columns defeat the prefetcher: 41 against 25 ms for the back substitution with
/// the 306 MB factor of BM_SupernodalSolve/160). Four partial sums, so that the additions' latency
/// does not bound the stream.
template <>
inline void add_dots<1>(const double* const* column, const double* __restrict x, int begin, int end,
                        double* dot) {
  const double* v = column[0];
  Pair s0 = {}, s1 = {}, s2 = {}, s3 = {};
  int i = end;
  for (; i - 8 >= begin;) {
    i -= 8;
    const double* xi = x + (i - begin);
    s3 += load_pair(v + i + 6) * load_pair(xi + 6);
    s2 += load_pair(v + i + 4) * load_pair(xi + 4);
    s1 += load_pair(v + i + 2) * load_pair(xi + 2);
    s0 += load_pair(v + i) * load_pair(xi);
  }
  const Pair s = (s0 + s1) + (s2 + s3);
  double sum = s[0] + s[1];
  while (i > begin) {
    --i;
    sum += v[i] * x[i - begin];
  }
  dot[0] += sum;
}

template <int W>
struct AddDots {
  static void run(const double* const* column, const double* x, int begin, int end, double* dot) {
    add_dots<W>(column, x, begin, end, dot);
  }
};

}  // namespace

void forward_substitution(const SupernodalLayout& f, double* y, std::vector<double>& work) {
  for (int s = 0; s < f.n_super; ++s) {
    const Supernode node = supernode(f, s);
    if (static_cast<int>(work.size()) < node.rows) work.resize(static_cast<std::size_t>(node.rows));
    // The supernode's rows of the right-hand side side by side: its own columns' entries, then
    // zeros that collect the update of the rows below. Each column then updates one contiguous
    // run of rows.
    double* t = work.data();
    double* ys = y + node.first_column;
    std::copy(ys, ys + node.columns, t);
    std::fill(t + node.columns, t + node.rows, 0.0);
    const int block = node.rows > f.long_column ? kBlock : 1;
    for (int j = 0; j < node.columns; j += block) {
      const int w = std::min(block, node.columns - j);
      const double* column[kBlock];
      for (int c = 0; c < w; ++c)
        column[c] = node.value + static_cast<std::ptrdiff_t>(j + c) * node.rows;
      // The block's own triangle, then its columns applied to every row after it.
      for (int c = 0; c < w; ++c) {
        t[j + c] /= column[c][j + c];
        for (int r = c + 1; r < w; ++r) t[j + r] -= column[c][j + r] * t[j + c];
      }
      with_width<SubtractColumns>(w, column, t + j, j + w, node.rows, t);
    }
    std::copy(t, t + node.columns, ys);
    const int* row = node.row;
    for (int i = node.columns; i < node.rows; ++i) y[row[i]] += t[i];
  }
}

void back_substitution(const SupernodalLayout& f, double* y, std::vector<double>& work) {
  for (int s = f.n_super - 1; s >= 0; --s) {
    const Supernode node = supernode(f, s);
    if (static_cast<int>(work.size()) < node.rows) work.resize(static_cast<std::size_t>(node.rows));
    // The supernode's rows of the solution side by side: its own columns' entries (solved
    // here, from the last), then the rows below (final: later supernodes).
    double* x = work.data();
    double* xs = y + node.first_column;
    std::copy(xs, xs + node.columns, x);
    const int* row = node.row;
    for (int i = node.columns; i < node.rows; ++i) x[i] = y[row[i]];
    // Column blocks from the last: every row after a block is final when the block is solved.
    const int block = node.rows > f.long_column ? kBlock : 1;
    const int last_block = ((node.columns - 1) / block) * block;
    for (int j = last_block; j >= 0; j -= block) {
      const int w = std::min(block, node.columns - j);
      const double* column[kBlock];
      for (int c = 0; c < w; ++c)
        column[c] = node.value + static_cast<std::ptrdiff_t>(j + c) * node.rows;
      double dot[kBlock] = {};
      with_width<AddDots>(w, column, x + j + w, j + w, node.rows, dot);
      for (int c = w - 1; c >= 0; --c) {
        double sum = x[j + c] - dot[c];
        for (int r = c + 1; r < w; ++r) sum -= column[c][j + r] * x[j + r];
        x[j + c] = sum / column[c][j + c];
      }
    }
    std::copy(x, x + node.columns, xs);
  }
}

}  // namespace impactfe
