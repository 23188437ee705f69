#include "linalg/supernodal_substitution.h"

#include <algorithm>
#include <cstring>
#include <optional>
#include <queue>

#include "core/errors.h"
#include "core/thread_pool.h"
#include "linalg/simd_pair.h"

namespace impactfe {

namespace {

using simd::load_pair;
using simd::Pair;

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

/// One supernode of the forward substitution: its own entries of y solved, and the update of
/// the rows below handed to `update(row, value)` (y[row] += value on one thread).
template <class Update>
void forward_supernode(const SupernodalLayout& f, int s, double* y, std::vector<double>& work,
                       Update&& update) {
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
  for (int i = node.columns; i < node.rows; ++i) update(row[i], t[i]);
}

/// One supernode of the back substitution: its own entries of y, from the final rows below.
void back_supernode(const SupernodalLayout& f, int s, double* y, std::vector<double>& work) {
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

}  // namespace

void forward_substitution(const SupernodalLayout& f, double* y, std::vector<double>& work) {
  for (int s = 0; s < f.n_super; ++s)
    forward_supernode(f, s, y, work, [y](int row, double value) { y[row] += value; });
}

void back_substitution(const SupernodalLayout& f, double* y, std::vector<double>& work) {
  for (int s = f.n_super - 1; s >= 0; --s) back_supernode(f, s, y, work);
}

namespace {

/// The supernodal elimination tree of a factor: a supernode's parent owns the first row below
/// its columns. Per supernode: its parent (-1 for a root), the first supernode of its subtree,
/// its weight (values of L) and its subtree's, and its children (child_start / children, in
/// ascending order).
struct EliminationTree {
  std::vector<int> parent, first, child_count, child_start, children;
  std::vector<long long> weight, subtree;
};

/// The tree of `f`, or nullopt when the supernodes are not in postorder (children first).
std::optional<EliminationTree> elimination_tree(const SupernodalLayout& f) {
  const int ns = f.n_super;
  const int n = f.super[ns];
  const auto nsz = static_cast<std::size_t>(ns);
  std::vector<int> owner(static_cast<std::size_t>(n));
  for (int s = 0; s < ns; ++s)
    std::fill(owner.begin() + f.super[s], owner.begin() + f.super[s + 1], s);
  EliminationTree t;
  t.parent.assign(nsz, -1);
  t.first.resize(nsz);
  t.weight.resize(nsz);
  t.child_count.assign(nsz + 1, 0);
  for (int s = 0; s < ns; ++s) {
    const auto k = static_cast<std::size_t>(s);
    t.first[k] = s;
    t.weight[k] = f.value_start[s + 1] - f.value_start[s];
    const int columns = f.super[s + 1] - f.super[s];
    if (f.row_start[s + 1] - f.row_start[s] > columns) {
      t.parent[k] = owner[static_cast<std::size_t>(f.rows[f.row_start[s] + columns])];
      if (t.parent[k] <= s) return std::nullopt;
      ++t.child_count[static_cast<std::size_t>(t.parent[k])];
    }
  }
  // Subtree weights and first supernodes (children come before their parent).
  t.subtree = t.weight;
  for (int s = 0; s < ns; ++s) {
    const int p = t.parent[static_cast<std::size_t>(s)];
    if (p < 0) continue;
    const auto pk = static_cast<std::size_t>(p), k = static_cast<std::size_t>(s);
    t.subtree[pk] += t.subtree[k];
    t.first[pk] = std::min(t.first[pk], t.first[k]);
  }
  t.child_start.assign(nsz + 1, 0);
  t.children.resize(nsz);
  for (int s = 0; s < ns; ++s)
    t.child_start[static_cast<std::size_t>(s) + 1] =
        t.child_start[static_cast<std::size_t>(s)] + t.child_count[static_cast<std::size_t>(s)];
  std::vector<int> next(t.child_start.begin(), t.child_start.end() - 1);
  for (int s = 0; s < ns; ++s)
    if (t.parent[static_cast<std::size_t>(s)] >= 0)
      t.children[static_cast<std::size_t>(
          next[static_cast<std::size_t>(t.parent[static_cast<std::size_t>(s)])]++)] = s;
  return t;
}

/// Cuts the tree at the root of its heaviest subtree, `cuts` times at most: the separators cut
/// off are solved on one thread, the subtrees left (`roots`) side by side. Returns the cost of
/// two threads after 0, 1, ... cuts: serial + max(heaviest subtree, rest / 2) of `total`.
std::vector<long long> cut_tree(const EliminationTree& t, long long total, int cuts,
                                std::vector<int>& separators, std::vector<int>& roots) {
  using Candidate = std::pair<long long, int>;  // (weight, root): the heaviest first, ties by root
  const int ns = static_cast<int>(t.parent.size());
  std::priority_queue<Candidate> open;
  for (int s = 0; s < ns; ++s)
    if (t.parent[static_cast<std::size_t>(s)] < 0)
      open.emplace(t.subtree[static_cast<std::size_t>(s)], s);
  long long serial = 0, heaviest_leaf = 0;
  std::vector<long long> cost;  // after 0, 1, ... cuts
  const auto record = [&] {
    const long long heaviest = std::max(open.empty() ? 0 : open.top().first, heaviest_leaf);
    cost.push_back(serial + std::max(heaviest, (total - serial + 1) / 2));
  };
  for (int done = 0;;) {
    while (!open.empty() && t.child_count[static_cast<std::size_t>(open.top().second)] == 0) {
      heaviest_leaf = std::max(heaviest_leaf, open.top().first);
      roots.push_back(open.top().second);  // a subtree of one supernode: not cut
      open.pop();
    }
    record();
    if (done == cuts || open.empty()) break;
    const int s = open.top().second;
    const auto k = static_cast<std::size_t>(s);
    open.pop();
    serial += t.weight[k];
    separators.push_back(s);
    for (int c = t.child_start[k]; c < t.child_start[k + 1]; ++c) {
      const int child = t.children[static_cast<std::size_t>(c)];
      open.emplace(t.subtree[static_cast<std::size_t>(child)], child);
    }
    ++done;
  }
  for (; !open.empty(); open.pop()) roots.push_back(open.top().second);
  return cost;
}

}  // namespace

void SubtreeSubstitution::plan(const SupernodalLayout& f, long long min_values) {
  n_super_ = f.n_super;
  groups_.clear();
  separators_.clear();
  separator_position_.clear();
  separator_column_.clear();
  serial_fraction_ = 1.0;
  const int ns = f.n_super;
  const long long total = ns > 0 ? f.value_start[ns] : 0;
  if (total < min_values) return;
  const std::optional<EliminationTree> tree = elimination_tree(f);
  if (!tree) return;  // not a postordered tree: stay serial
  // Cut the tree at the root of its heaviest subtree, again and again. Of the first kMaxCuts
  // cuts in that order, keep as many as give two threads the least work (a structural choice:
  // the plan is the same for any thread count). A 3-D mesh's top separators are dense and heavy
  // (a sixth of L on a brick block), a shell's are light.
  constexpr int kMaxCuts = 64;
  std::vector<int> roots;
  const std::vector<long long> cost = cut_tree(*tree, total, kMaxCuts, separators_, roots);
  const int best = static_cast<int>(std::min_element(cost.begin(), cost.end()) - cost.begin());
  separators_.clear();
  roots.clear();
  cut_tree(*tree, total, best, separators_, roots);
  long long serial = 0;
  for (int s : separators_) serial += tree->weight[static_cast<std::size_t>(s)];
  if (roots.size() < 2) {
    separators_.clear();
    return;
  }
  std::sort(separators_.begin(), separators_.end());
  separator_position_.assign(static_cast<std::size_t>(f.super[ns]), -1);
  for (int s : separators_)
    for (int c = f.super[s]; c < f.super[s + 1]; ++c) {
      separator_position_[static_cast<std::size_t>(c)] = static_cast<int>(separator_column_.size());
      separator_column_.push_back(c);
    }
  pack_groups(f, tree->subtree, tree->first, roots);
  if (!groups_update_only_separators(f)) {
    groups_.clear();
    separators_.clear();
    return;
  }
  serial_fraction_ = static_cast<double>(serial) / static_cast<double>(total);
}

void SubtreeSubstitution::pack_groups(const SupernodalLayout& f,
                                      const std::vector<long long>& subtree,
                                      const std::vector<int>& first, std::vector<int>& roots) {
  // The subtrees into groups, the heaviest first, each to the lightest group (the first of
  // equal ones): a fixed packing, whatever the thread count.
  std::sort(roots.begin(), roots.end(), [&](int a, int b) {
    const long long wa = subtree[static_cast<std::size_t>(a)],
                    wb = subtree[static_cast<std::size_t>(b)];
    return wa != wb ? wa > wb : a < b;
  });
  const int n_groups = std::min<int>(kGroups, static_cast<int>(roots.size()));
  groups_.resize(static_cast<std::size_t>(n_groups));
  std::vector<long long> load(static_cast<std::size_t>(n_groups), 0);
  for (int root : roots) {
    const auto g =
        static_cast<std::size_t>(std::min_element(load.begin(), load.end()) - load.begin());
    const auto k = static_cast<std::size_t>(root);
    load[g] += subtree[k];
    groups_[g].subtrees.push_back(Subtree{first[k], root, f.super[root + 1]});
    // The separator rows a subtree updates are its root's rows below (the rows below any of its
    // columns outside the subtree are rows of its root's: George & Liu 1981).
    const int columns = f.super[root + 1] - f.super[root];
    for (int i = f.row_start[root] + columns; i < f.row_start[root + 1]; ++i)
      groups_[g].touched.push_back(separator_position_[static_cast<std::size_t>(f.rows[i])]);
  }
}

bool SubtreeSubstitution::groups_update_only_separators(const SupernodalLayout& f) {
  std::vector<unsigned char> touched(separator_column_.size(), 0);
  for (Group& group : groups_) {
    // Within a group, the subtrees in postorder.
    std::sort(group.subtrees.begin(), group.subtrees.end(),
              [](const Subtree& a, const Subtree& b) { return a.first < b.first; });
    std::sort(group.touched.begin(), group.touched.end());
    group.touched.erase(std::unique(group.touched.begin(), group.touched.end()),
                        group.touched.end());
    group.update.assign(separator_column_.size(), 0.0);
    // Every row a subtree updates outside itself is one of those (a factor whose supernodes
    // broke the rule would stay on one thread rather than update a row no buffer holds).
    for (int p : group.touched) touched[static_cast<std::size_t>(p)] = 1;
    for (const Subtree& t : group.subtrees)
      for (int i = f.row_start[t.first]; i < f.row_start[t.last + 1]; ++i) {
        const int row = f.rows[i];
        if (row < t.end_column) continue;
        const int p = separator_position_[static_cast<std::size_t>(row)];
        if (p < 0 || !touched[static_cast<std::size_t>(p)]) return false;
      }
    for (int p : group.touched) touched[static_cast<std::size_t>(p)] = 0;
  }
  return true;
}

void SubtreeSubstitution::forward(const SupernodalLayout& f, double* y) {
  if (groups_.empty()) {
    forward_substitution(f, y, work_);
    return;
  }
  IMPACTFE_CHECK(f.n_super == n_super_, "SubtreeSubstitution: the factor changed since its plan");
  threads::parallel_for(groups(), 1, [&](int g) {
    Group& group = groups_[static_cast<std::size_t>(g)];
    double* update = group.update.data();
    const int* position = separator_position_.data();
    for (const Subtree& t : group.subtrees) {
      const int end_column = t.end_column;
      for (int s = t.first; s <= t.last; ++s)
        forward_supernode(f, s, y, group.work, [&](int row, double value) {
          if (row < end_column)
            y[row] += value;
          else
            update[position[row]] += value;
        });
    }
  });
  for (Group& group : groups_)
    for (int p : group.touched) {
      y[separator_column_[static_cast<std::size_t>(p)]] +=
          group.update[static_cast<std::size_t>(p)];
      group.update[static_cast<std::size_t>(p)] = 0.0;
    }
  for (int s : separators_)
    forward_supernode(f, s, y, work_, [y](int row, double value) { y[row] += value; });
}

void SubtreeSubstitution::back(const SupernodalLayout& f, double* y) {
  if (groups_.empty()) {
    back_substitution(f, y, work_);
    return;
  }
  IMPACTFE_CHECK(f.n_super == n_super_, "SubtreeSubstitution: the factor changed since its plan");
  for (auto s = separators_.rbegin(); s != separators_.rend(); ++s) back_supernode(f, *s, y, work_);
  threads::parallel_for(groups(), 1, [&](int g) {
    Group& group = groups_[static_cast<std::size_t>(g)];
    for (auto t = group.subtrees.rbegin(); t != group.subtrees.rend(); ++t)
      for (int s = t->last; s >= t->first; --s) back_supernode(f, s, y, group.work);
  });
}

}  // namespace impactfe
