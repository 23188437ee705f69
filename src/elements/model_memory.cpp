#include "elements/model_memory.h"

#include <fmt/format.h>

#include <algorithm>
#include <cmath>
#include <map>

#include "core/memory_budget.h"
#include "elements/element_registry.h"

namespace impactfe {

namespace {

// Bytes per entity, measured on this program's containers (std::map nodes, element records
// with their source location) and element classes, rounded down.
constexpr double kNodeBytes = 120.0;
constexpr double kElementRecordBytes = 200.0;
constexpr double kElementObjectBytes = 600.0;
constexpr double kMatrixEntryBytes = 12.0;  // value and row index
constexpr double kFactorEntryBytes = 8.0;
constexpr double kSolidFill = 9.0;  // half of nnz(L) / n^(4/3) on cube meshes of SOLID185

/// DOFs per node of an element type (its family) and whether it is a 3-D solid (its role).
std::pair<double, bool> dofs_per_node(const ElementTypeDescriptor& d) {
  if (d.role == ShapeRole::Solid) return {3.0, true};
  if (d.role == ShapeRole::Plane) return {2.0, false};
  if (d.family == "Shell4" || d.family == "Beam" || d.family == "QuadraticBeam")
    return {6.0, false};
  return {3.0, false};
}

struct Counts {
  double elements = 0.0, element_nodes = 0.0, matrix = 0.0, dofs_weight = 0.0, solid = 0.0;
  bool all_explicit = true;  // every element has an explicit kernel: the run is explicit
};

void add(Counts& c, const ElementTypeDescriptor& d, double count) {
  const auto [per_node, solid] = dofs_per_node(d);
  const double n = std::max(1, d.n_nodes) * per_node;  // element DOFs
  c.elements += count;
  c.element_nodes += count * std::max(1, d.n_nodes);
  // Lower-triangle entries of the element matrices, shared between neighbours: a structured
  // brick mesh has ≈ 41 per DOF, 300 / 2.5 per element.
  c.matrix += count * n * (n + 1.0) / 2.0 / 2.5;
  c.dofs_weight += count * per_node;
  if (solid) c.solid += count;
  if (!d.explicit_set) c.all_explicit = false;
}

}  // namespace

std::string ModelMemory::describe() const {
  return fmt::format(
      "{:.0f} nodes, {:.0f} elements, about {:.3g} equations: database {}, elements {}, "
      "matrices {}, factor {}{}",
      nodes, elements, dofs, format_bytes(database), format_bytes(structure),
      format_bytes(matrices), format_bytes(factor),
      results > 0.0 ? ", results block " + format_bytes(results) : std::string());
}

ModelMemory estimate_model_memory(const Model& model, int added_type, double added_nodes,
                                  double added_elements) {
  Counts c;
  std::map<int, std::pair<const ElementTypeDescriptor*, double>> by_type;
  for (const auto& [id, e] : model.elements) {
    auto& slot = by_type[e.type];
    if (!slot.first) {
      const auto t = model.element_types.find(e.type);
      slot.first =
          t == model.element_types.end() ? nullptr : find_element_type(t->second.ansys_name);
    }
    slot.second += 1.0;
  }
  if (added_type > 0 && added_elements > 0) {
    auto& slot = by_type[added_type];
    const auto t = model.element_types.find(added_type);
    if (t != model.element_types.end()) slot.first = find_element_type(t->second.ansys_name);
    slot.second += added_elements;
  }
  for (const auto& [type, entry] : by_type)
    if (entry.first) add(c, *entry.first, entry.second);
  ModelMemory m;
  m.nodes = static_cast<double>(model.nodes.size()) + added_nodes;
  m.elements = c.elements;
  // DOFs: the nodes times the DOFs per node of the elements on them (weighted by count).
  const double per_node = c.elements > 0.0 ? c.dofs_weight / c.elements : 3.0;
  m.dofs = m.nodes * per_node;
  m.solid_dofs = c.elements > 0.0 ? m.dofs * c.solid / c.elements : 0.0;
  m.database = m.nodes * kNodeBytes + c.elements * kElementRecordBytes + c.element_nodes * 4.0;
  m.structure = c.elements * kElementObjectBytes;
  // One block of stored points being filled (results/result_series.h, block_rows_for): every
  // nodal quantity (4 of 6 components) and element value (24) of a point, 64 points, fewer
  // down to 4 when that passes 32 MB.
  const double row_bytes = 8.0 * (24.0 * m.nodes + 24.0 * c.elements + 16.0);
  m.results = std::max(std::min(64.0 * row_bytes, 32.0 * 1024 * 1024), 4.0 * row_bytes);
  // An explicit run (every element with an explicit kernel, as the solve decides) keeps no
  // matrix: its lumped mass, forces, velocities and displacements are DOF vectors.
  if (c.all_explicit && c.elements > 0.0) {
    m.matrices = 20.0 * m.dofs * 8.0;
    return m;
  }
  // The stiffness, the mass and the effective matrix (the linear parts' sums and the one
  // factored), with the DOF vectors of a solve.
  m.matrices = 3.0 * c.matrix * kMatrixEntryBytes + 20.0 * m.dofs * 8.0;
  const double factor_entries =
      std::max(c.matrix, kSolidFill * std::pow(std::max(m.solid_dofs, 0.0), 4.0 / 3.0));
  m.factor = factor_entries * kFactorEntryBytes;
  return m;
}

void require_model_memory(const Model& model, const std::string& what, int added_type,
                          double added_nodes, double added_elements) {
  const ModelMemory need = estimate_model_memory(model, added_type, added_nodes, added_elements);
  const MemoryAvailable available = memory_available();
  if (need.total() <= available.bytes) return;
  // What would fit: the same kind of model scaled down (bisection on the scale of the counts).
  double lo = 0.0, hi = 1.0;
  for (int i = 0; i < 40; ++i) {
    const double s = 0.5 * (lo + hi);
    ModelMemory scaled = need;
    scaled.nodes *= s;
    const double solid_ratio = need.dofs > 0 ? need.solid_dofs / need.dofs : 0.0;
    scaled.dofs = need.dofs * s;
    scaled.solid_dofs = scaled.dofs * solid_ratio;
    scaled.database = need.database * s;
    scaled.structure = need.structure * s;
    scaled.results = need.results * s;
    scaled.matrices = need.matrices * s;
    scaled.factor =
        need.factor <= 0.0  // an explicit run factors nothing
            ? 0.0
            : std::max(need.matrices * s / 3.0 * kFactorEntryBytes / kMatrixEntryBytes,
                       kSolidFill * std::pow(scaled.solid_dofs, 4.0 / 3.0) * kFactorEntryBytes);
    (scaled.total() <= available.bytes ? lo : hi) = s;
  }
  throw MemoryLimitError(fmt::format(
      "{}: the model ({}) needs about {} in all, more than the {} this run may still take ({}); "
      "about {:.0f} elements of this kind would fit (a coarser mesh), or give the run more "
      "memory",
      what, need.describe(), format_bytes(need.total()), format_bytes(available.bytes),
      available.source, lo * need.elements));
}

}  // namespace impactfe
