#pragma once
/// An estimate of the memory a model needs to be solved, from its counts alone (nodes,
/// elements and their types), made before anything large is built: before a mesh is generated
/// and before a SOLVE builds the structure (docs/reliability.md, "Memory"). The solve's exact
/// figure comes later from the symbolic analysis (nnz(L)); this one is made to refuse quickly
/// what cannot fit, and so errs low: a 3-D solid mesh's factor is taken at half the fill
/// measured on cube meshes (nnz(L) ≈ 18 n^(4/3) for n equations), any other factor at no more
/// than the stiffness matrix itself.
#include <string>

#include "core/model.h"

namespace impactfe {

struct ModelMemory {
  double nodes = 0.0, elements = 0.0, dofs = 0.0, solid_dofs = 0.0;
  double database = 0.0;   // nodes and element records of the deck's model
  double structure = 0.0;  // the element objects of a solve
  double matrices = 0.0;   // stiffness, mass and effective matrices (lower triangles)
  double factor = 0.0;     // the factor L of the effective matrix (estimate, errs low)
  double results = 0.0;    // one block of stored points being filled
  double total() const { return database + structure + matrices + factor + results; }
  std::string describe() const;
};

/// The estimate for `model` with `added_nodes` nodes and `added_elements` elements of element
/// type `added_type` (0: none) more.
ModelMemory estimate_model_memory(const Model& model, int added_type = 0, double added_nodes = 0,
                                  double added_elements = 0);

/// Throws MemoryLimitError (core/memory_budget.h) when the estimate exceeds what the run may
/// still take, `what` saying for what ("meshing volume 1", "the static analysis"), with the
/// model's size and about how many elements of the same kind would fit.
void require_model_memory(const Model& model, const std::string& what, int added_type = 0,
                          double added_nodes = 0, double added_elements = 0);

}  // namespace impactfe
