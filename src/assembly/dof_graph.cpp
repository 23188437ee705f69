#include "assembly/dof_graph.h"

#include <algorithm>
#include <limits>

#include "core/errors.h"

namespace impactfe {

DofGraph::DofGraph(const DofMap& dofs, std::size_t n_elements) {
  const int n = dofs.n_active();
  const auto un = static_cast<std::size_t>(n);
  // The elements at each DOF (incidence lists, counting sort).
  std::vector<std::size_t> incidence_start(un + 1, 0);
  for (std::size_t e = 0; e < n_elements; ++e)
    for (int i : dofs.element_indices(e)) ++incidence_start[static_cast<std::size_t>(i) + 1];
  for (std::size_t i = 0; i < un; ++i) incidence_start[i + 1] += incidence_start[i];
  std::vector<std::size_t> incidence(incidence_start[un]);
  {
    std::vector<std::size_t> next(incidence_start.begin(), incidence_start.end() - 1);
    for (std::size_t e = 0; e < n_elements; ++e)
      for (int i : dofs.element_indices(e)) incidence[next[static_cast<std::size_t>(i)]++] = e;
  }
  // Row i: the DOFs of the elements at i, each once (a marker per DOF), sorted.
  std::vector<int> marker(un, -1);
  row_start_.reserve(un + 1);
  row_start_.push_back(0);
  for (int i = 0; i < n; ++i) {
    const std::size_t begin = column_.size();
    marker[static_cast<std::size_t>(i)] = i;
    column_.push_back(i);
    for (std::size_t k = incidence_start[static_cast<std::size_t>(i)];
         k < incidence_start[static_cast<std::size_t>(i) + 1]; ++k)
      for (int j : dofs.element_indices(incidence[k]))
        if (marker[static_cast<std::size_t>(j)] != i) {
          marker[static_cast<std::size_t>(j)] = i;
          column_.push_back(j);
        }
    std::sort(column_.begin() + static_cast<std::ptrdiff_t>(begin), column_.end());
    IMPACTFE_CHECK(column_.size() <= static_cast<std::size_t>(std::numeric_limits<int>::max()),
                   "DofGraph: more than 2^31 matrix entries");
    row_start_.push_back(static_cast<int>(column_.size()));
  }
  column_.shrink_to_fit();
}

void DofGraph::element_slots(const std::vector<int>& idx, std::vector<int>& slots) const {
  const std::size_t n = idx.size();
  slots.resize(n * n);
  for (std::size_t a = 0; a < n; ++a) {
    const auto row = static_cast<std::size_t>(idx[a]);
    const int* begin = column_.data() + row_start_[row];
    const int* end = column_.data() + row_start_[row + 1];
    for (std::size_t b = 0; b < n; ++b)
      slots[a * n + b] = static_cast<int>(std::lower_bound(begin, end, idx[b]) - column_.data());
  }
}

SparsePattern DofGraph::lower_pattern(int n) const {
  // Column c of the lower triangle = the entries r >= c (r < n) of row c (symmetric graph).
  SparsePattern p;
  p.size = n;
  p.column_start.assign(static_cast<std::size_t>(n) + 1, 0);
  for (int c = 0; c < n; ++c) {
    const int* begin = column_.data() + row_start_[static_cast<std::size_t>(c)];
    const int* end = column_.data() + row_start_[static_cast<std::size_t>(c) + 1];
    for (const int* r = std::lower_bound(begin, end, c); r != end && *r < n; ++r)
      p.row.push_back(*r);
    p.column_start[static_cast<std::size_t>(c) + 1] = static_cast<int>(p.row.size());
  }
  p.row.shrink_to_fit();
  return p;
}

void GraphMatrix::add(const std::vector<int>& slots, const MatrixXd& m, bool transposed) {
  const auto n = static_cast<std::size_t>(m.rows());
  for (std::size_t a = 0; a < n; ++a)
    for (std::size_t b = 0; b < n; ++b) {
      const double x = m(static_cast<Eigen::Index>(a), static_cast<Eigen::Index>(b));
      if (x == 0.0) continue;
      if (value.empty()) {
        value.assign(n_entries, 0.0);
        touched.assign(n_entries, 0);
      }
      const auto s = static_cast<std::size_t>(transposed ? slots[b * n + a] : slots[a * n + b]);
      value[s] += x;
      touched[s] = 1;
    }
}

SparseMatrix GraphMatrix::to_sparse(const DofGraph& graph) const {
  const int n = graph.size();
  const auto& row_start = graph.row_start();
  const auto& column = graph.column();
  std::vector<int> outer(static_cast<std::size_t>(n) + 1, 0);
  if (value.empty()) return SparseMatrix(n, n);
  std::vector<int> inner;
  std::vector<double> values;
  for (int i = 0; i < n; ++i) {
    for (int k = row_start[static_cast<std::size_t>(i)];
         k < row_start[static_cast<std::size_t>(i) + 1]; ++k)
      if (touched[static_cast<std::size_t>(k)]) {
        inner.push_back(column[static_cast<std::size_t>(k)]);
        values.push_back(value[static_cast<std::size_t>(k)]);
      }
    outer[static_cast<std::size_t>(i) + 1] = static_cast<int>(inner.size());
  }
  return Eigen::Map<const SparseMatrix>(n, n, static_cast<Eigen::Index>(inner.size()), outer.data(),
                                        inner.data(), values.data());
}

}  // namespace impactfe
