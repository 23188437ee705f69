#pragma once
/// CDWRITE,DB: the model as a CDB archive that CDREAD (impactfe's or MAPDL's) reads back: element
/// types and KEYOPTs, real constant sets (RLBLOCK), material properties (MPDATA) and tables
/// (TB), sections, local coordinate systems (LOCAL,R5.0), nodes (NBLOCK, with rotation angles),
/// elements (EBLOCK, solid format), node and element components (CMBLOCK), coupled sets (CP),
/// constraint equations (CE,R5.0), rigid regions (CERIG), and the current constraints, forces,
/// face pressures (SFE,R5.0), temperatures, accelerations, initial conditions and master DOFs.
/// Reals are written with 17 significant digits, so a write, read, write gives the same file, the
/// same model and the same solution. The solid model is not written (as CDWRITE,DB).
#include <ostream>

#include "core/model.h"

namespace impactfe::deck {

/// Throws std::invalid_argument for what a CDB cannot hold here (superelements, GP gap
/// conditions, table loads, imaginary forces, LVSCALE), so that nothing is left out silently.
void write_cdb(const Model& model, std::ostream& out);

}  // namespace impactfe::deck
