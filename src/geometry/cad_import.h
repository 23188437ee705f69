#pragma once
/// CAD files in the solid model (IGESIN; STEP files alike): Gmsh's OpenCASCADE importer reads
/// the file, and its points, curves, surfaces and volumes become keypoints, lines, areas and
/// volumes, numbered from the NUMSTR starts upward (lowest free numbers), which VMESH and AMESH
/// then mesh like any other (free meshing: geometry/free_mesher.cpp).
#include <string>

#include "core/errors.h"
#include "core/model.h"

namespace impactfe::geometry {

struct CadImportCounts {
  int keypoints = 0;
  int lines = 0;
  int areas = 0;
  int volumes = 0;
};

/// Reads `path` (IGES: .igs/.iges, STEP: .stp/.step) into the solid model. IGES coordinates
/// are taken in the file's own length unit (no conversion, as MAPDL reads them), STEP ones in
/// millimetres. Straight
/// lines, circular arcs, planar areas and 3- or 4-sided cylindrical or conical areas are
/// carried over; any other curve or surface is refused (InputError at `where`, nothing added).
CadImportCounts import_cad(Model& model, const std::string& path, const SourceLocation& where);

/// Sum of the volumes (dim 3) or areas (dim 2) of the file's shapes as OpenCASCADE integrates
/// them (for checks of a mesh against its CAD model).
double cad_measure(const std::string& path, int dim);

}  // namespace impactfe::geometry
