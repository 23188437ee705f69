#pragma once
/// A Gmsh session for the free mesher and the CAD importer: Gmsh keeps its model in global
/// state, so a session opens and closes around each operation, with one thread and fixed
/// options so that the same input gives the same mesh. Gmsh is reached through gmsh_api.h.
#include <fmt/format.h>

#include <exception>
#include <string>

#include "core/errors.h"
#include "geometry/gmsh_api.h"

namespace impactfe::geometry {

/// One Gmsh session: Gmsh keeps its model in global state, so a session opens and closes
/// around each meshing operation, with the options that make its output reproducible.
class GmshSession {
 public:
  explicit GmshSession(const std::string& name) {
    gmsh::initialize(0, nullptr, false);
    gmsh::option::setNumber("General.Terminal", 0);
    gmsh::option::setNumber("General.Verbosity", 0);
    gmsh::option::setNumber("General.NumThreads", 1);
    gmsh::option::setNumber("Mesh.RandomSeed", 1);
    gmsh::option::setNumber("Mesh.Algorithm", 6);    // Frontal-Delaunay (2-D)
    gmsh::option::setNumber("Mesh.Algorithm3D", 1);  // Delaunay (3-D)
    gmsh::option::setNumber("Mesh.Optimize", 1);
    gmsh::option::setNumber("Mesh.ElementOrder", 1);
    gmsh::model::add(name);
  }
  ~GmshSession() {
    try {
      gmsh::finalize();
    } catch (...) {
    }
  }
  GmshSession(const GmshSession&) = delete;
  GmshSession& operator=(const GmshSession&) = delete;
};

/// Runs f, turning Gmsh's errors (std::runtime_error from gmsh_api.h) into an InputError
/// "Gmsh could not <what>: <message>".
template <class F>
void with_gmsh(const SourceLocation& where, const std::string& what, F&& f) {
  try {
    f();
  } catch (const std::exception& e) {
    if (dynamic_cast<const InputError*>(&e) != nullptr) throw;
    throw InputError(where, fmt::format("Gmsh could not {}: {}", what, e.what()));
  }
}

}  // namespace impactfe::geometry
