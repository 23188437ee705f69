#pragma once
/// The part of Gmsh's API the free mesher and the CAD importer use, with the signatures of
/// Gmsh's C++ API (gmsh.h, 4.8), reached through its C API in a library loaded at the first
/// call (dlopen of the libgmsh that CMake found). Not linking libgmsh keeps impactfe's start-up
/// as it was: libgmsh maps about 90 libraries (OpenCASCADE, BLAS, ...), about 0.3 s for every
/// run, where only a deck that meshes free or reads a CAD file needs them. Only C types cross
/// to the library, so impactfe keeps its own static libstdc++.
///
/// Errors (a Gmsh error, or the library that cannot be loaded) are std::runtime_error with
/// Gmsh's message.
#include <string>
#include <utility>
#include <vector>

namespace impactfe::geometry::gmsh {

using vectorpair = std::vector<std::pair<int, int>>;

void initialize(int argc = 0, char** argv = nullptr, bool readConfigFiles = true);
void finalize();
void write(const std::string& fileName);

namespace option {
void setNumber(const std::string& name, double value);
void setString(const std::string& name, const std::string& value);
}  // namespace option

namespace model {
void add(const std::string& name);
int addDiscreteEntity(int dim, int tag = -1, const std::vector<int>& boundary = {});
void getEntities(vectorpair& dimTags, int dim = -1);
void getAdjacencies(int dim, int tag, std::vector<int>& upward, std::vector<int>& downward);
void getBoundary(const vectorpair& dimTags, vectorpair& outDimTags, bool combined = true,
                 bool oriented = true, bool recursive = false);
void getParametrizationBounds(int dim, int tag, std::vector<double>& min, std::vector<double>& max);
void getType(int dim, int tag, std::string& entityType);
void getValue(int dim, int tag, const std::vector<double>& parametricCoord,
              std::vector<double>& coord);

namespace geo {
int addPoint(double x, double y, double z, double meshSize = 0.0, int tag = -1);
int addLine(int startTag, int endTag, int tag = -1);
int addCircleArc(int startTag, int centerTag, int endTag, int tag = -1);
int addSpline(const std::vector<int>& pointTags, int tag = -1);
int addCurveLoop(const std::vector<int>& curveTags, int tag = -1);
int addPlaneSurface(const std::vector<int>& wireTags, int tag = -1);
int addSurfaceFilling(const std::vector<int>& wireTags, int tag = -1);
int addSurfaceLoop(const std::vector<int>& surfaceTags, int tag = -1);
int addVolume(const std::vector<int>& shellTags, int tag = -1);
void synchronize();
}  // namespace geo

namespace mesh {
void generate(int dim = 3);
void getNodes(std::vector<std::size_t>& nodeTags, std::vector<double>& coord,
              std::vector<double>& parametricCoord, int dim = -1, int tag = -1,
              bool includeBoundary = false, bool returnParametricCoord = true);
void addNodes(int dim, int tag, const std::vector<std::size_t>& nodeTags,
              const std::vector<double>& coord);
void addElementsByType(int tag, int elementType, const std::vector<std::size_t>& elementTags,
                       const std::vector<std::size_t>& nodeTags);
void getElements(std::vector<int>& elementTypes, std::vector<std::vector<std::size_t>>& elementTags,
                 std::vector<std::vector<std::size_t>>& nodeTags, int dim = -1, int tag = -1);
void getElementsByType(int elementType, std::vector<std::size_t>& elementTags,
                       std::vector<std::size_t>& nodeTags, int tag = -1);
void setRecombine(int dim, int tag);
void setTransfiniteCurve(int tag, int numNodes, const std::string& meshType = "Progression",
                         double coef = 1.0);
}  // namespace mesh

namespace occ {
void importShapes(const std::string& fileName, vectorpair& outDimTags, bool highestDimOnly = true);
void synchronize();
void getEntities(vectorpair& dimTags, int dim = -1);
void dilate(const vectorpair& dimTags, double x, double y, double z, double a, double b, double c);
void getMass(int dim, int tag, double& mass);
int addPoint(double x, double y, double z, double meshSize = 0.0, int tag = -1);
int addCylinder(double x, double y, double z, double dx, double dy, double dz, double r,
                int tag = -1, double angle = 2 * 3.14159265358979323846);
int addBSpline(const std::vector<int>& pointTags, int tag = -1);
}  // namespace occ
}  // namespace model

}  // namespace impactfe::geometry::gmsh
