#pragma once
/// CDWRITE,DB: the model as a CDB archive that CDREAD (impactfe's or MAPDL's) reads back: element
/// types and KEYOPTs, real constant sets (RLBLOCK), material properties (MPDATA) and tables
/// (TB), sections, nodes (NBLOCK, with rotation angles), elements (EBLOCK, solid format), node
/// and element components (CMBLOCK), and the current constraints, forces, accelerations, initial
/// conditions and master DOFs. Reals are written with 17 significant digits, so a write, read,
/// write gives the same file and the same model. The solid model is not written (as CDWRITE,DB).
#include <ostream>

#include "core/model.h"

namespace impactfe::deck {

/// Throws std::invalid_argument for what a CDB cannot hold here (superelements, GP gap
/// conditions, table and surface loads).
void write_cdb(const Model& model, std::ostream& out);

}  // namespace impactfe::deck
