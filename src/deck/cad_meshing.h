#pragma once
/// `impactfe mesh`: a CAD file (IGES or STEP) read into the solid model and meshed by Gmsh as the
/// deck IGESIN, ESIZE, MSHAPE, VMESH / AMESH would (src/geometry/free_mesher.cpp).
#include <string>

#include "core/model.h"

namespace impactfe::deck {

struct CadMeshRequest {
  std::string file;          // .igs, .iges, .stp, .step
  std::string type = "187";  // ANSYS element name or number
  double esize = 0.0;        // ESIZE; 0: DESIZE's sizes
  bool triangles = false;    // areas: MSHAPE,1 (triangles) instead of quadrilaterals
};

/// The meshed model: the volumes for a solid element type, the areas for any other (a type that
/// takes shell sections gets a unit-thickness one). Throws InputError for an unknown type or
/// what the deck commands refuse.
Model mesh_cad_file(const CadMeshRequest& request);

/// The worst element shapes of the whole mesh (geometry/mesh_quality.h) as the lines `impactfe
/// mesh` prints: "quality: ..." and, when elements are past the limits, a second line naming
/// the first; empty for a mesh without area or volume elements.
std::string mesh_quality_lines(const Model& model);

}  // namespace impactfe::deck
