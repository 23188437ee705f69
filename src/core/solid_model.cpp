#include "core/solid_model.h"

namespace impactfe {

int AreaGrid::at(int i, int j) const {
  if (!triangular) return nodes[static_cast<std::size_t>(i + j * (n1 + 1))];
  // Row j of the lattice holds n1 − j + 1 nodes; rows before it hold j (n1 + 1) − j (j − 1) / 2.
  return nodes[static_cast<std::size_t>(j * (n1 + 1) - j * (j - 1) / 2 + i)];
}

}  // namespace impactfe
