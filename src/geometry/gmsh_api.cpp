// Gmsh through its C API (gmshc.h) in a library loaded at the first call (gmsh_api.h says why).
// gmshc.h gives the functions' types only: nothing here links against libgmsh; each call looks
// its function up in the loaded library.
#include "geometry/gmsh_api.h"

#include <dlfcn.h>
#include <gmshc.h>

#include <mutex>
#include <stdexcept>

namespace impactfe::geometry::gmsh {

namespace {

/// The library CMake found (IMPACTFE_GMSH_LIBRARY), loaded once.
void* library() {
  static void* handle = nullptr;
  static std::string error;
  static std::once_flag once;
  std::call_once(once, [] {
    handle = dlopen(IMPACTFE_GMSH_LIBRARY, RTLD_NOW | RTLD_LOCAL);
    if (handle == nullptr) error = dlerror();
  });
  if (handle == nullptr)
    throw std::runtime_error(std::string("cannot load Gmsh (") + IMPACTFE_GMSH_LIBRARY +
                             "): " + error + " (scripts/install-deps.sh installs libgmsh-dev)");
  return handle;
}

template <class F>
F function(const char* name) {
  void* p = dlsym(library(), name);
  if (p == nullptr) throw std::runtime_error(std::string("Gmsh has no function ") + name);
  return reinterpret_cast<F>(p);
}

#define GMSH(name) function<decltype(&::name)>(#name)

/// Throws Gmsh's last error message when a call failed.
void check(int ierr) {
  if (ierr == 0) return;
  char* message = nullptr;
  int ierr2 = 0;
  GMSH(gmshLoggerGetLastError)(&message, &ierr2);
  std::string text = message != nullptr && *message != '\0' ? message : "error";
  if (message != nullptr) GMSH(gmshFree)(message);
  throw std::runtime_error(text);
}

/// Copies an array Gmsh allocated into a vector and frees it.
template <class T>
std::vector<T> take(T* p, std::size_t n) {
  std::vector<T> out(p, p + n);
  if (p != nullptr) GMSH(gmshFree)(p);
  return out;
}

vectorpair pairs(int* p, std::size_t n) {
  const std::vector<int> flat = take(p, n);
  vectorpair out;
  for (std::size_t i = 0; i + 1 < flat.size(); i += 2) out.emplace_back(flat[i], flat[i + 1]);
  return out;
}

std::vector<int> flat(const vectorpair& v) {
  std::vector<int> out;
  for (const auto& [a, b] : v) out.insert(out.end(), {a, b});
  return out;
}

}  // namespace

void initialize(int argc, char** argv, bool readConfigFiles) {
  int ierr = 0;
  GMSH(gmshInitialize)(argc, argv, readConfigFiles ? 1 : 0, &ierr);
  check(ierr);
}

void finalize() {
  int ierr = 0;
  GMSH(gmshFinalize)(&ierr);
  check(ierr);
}

void write(const std::string& fileName) {
  int ierr = 0;
  GMSH(gmshWrite)(fileName.c_str(), &ierr);
  check(ierr);
}

void option::setNumber(const std::string& name, double value) {
  int ierr = 0;
  GMSH(gmshOptionSetNumber)(name.c_str(), value, &ierr);
  check(ierr);
}

void option::setString(const std::string& name, const std::string& value) {
  int ierr = 0;
  GMSH(gmshOptionSetString)(name.c_str(), value.c_str(), &ierr);
  check(ierr);
}

void model::add(const std::string& name) {
  int ierr = 0;
  GMSH(gmshModelAdd)(name.c_str(), &ierr);
  check(ierr);
}

int model::addDiscreteEntity(int dim, int tag, const std::vector<int>& boundary) {
  int ierr = 0;
  std::vector<int> b = boundary;
  const int out = GMSH(gmshModelAddDiscreteEntity)(dim, tag, b.data(), b.size(), &ierr);
  check(ierr);
  return out;
}

void model::getEntities(vectorpair& dimTags, int dim) {
  int ierr = 0;
  int* p = nullptr;
  std::size_t n = 0;
  GMSH(gmshModelGetEntities)(&p, &n, dim, &ierr);
  dimTags = pairs(p, n);
  check(ierr);
}

void model::getAdjacencies(int dim, int tag, std::vector<int>& upward, std::vector<int>& downward) {
  int ierr = 0;
  int *up = nullptr, *down = nullptr;
  std::size_t nu = 0, nd = 0;
  GMSH(gmshModelGetAdjacencies)(dim, tag, &up, &nu, &down, &nd, &ierr);
  upward = take(up, nu);
  downward = take(down, nd);
  check(ierr);
}

void model::getBoundary(const vectorpair& dimTags, vectorpair& outDimTags, bool combined,
                        bool oriented, bool recursive) {
  int ierr = 0;
  std::vector<int> in = flat(dimTags);
  int* p = nullptr;
  std::size_t n = 0;
  GMSH(gmshModelGetBoundary)(in.data(), in.size(), &p, &n, combined, oriented, recursive, &ierr);
  outDimTags = pairs(p, n);
  check(ierr);
}

void model::getParametrizationBounds(int dim, int tag, std::vector<double>& min,
                                     std::vector<double>& max) {
  int ierr = 0;
  double *lo = nullptr, *hi = nullptr;
  std::size_t nl = 0, nh = 0;
  GMSH(gmshModelGetParametrizationBounds)(dim, tag, &lo, &nl, &hi, &nh, &ierr);
  min = take(lo, nl);
  max = take(hi, nh);
  check(ierr);
}

void model::getType(int dim, int tag, std::string& entityType) {
  int ierr = 0;
  char* p = nullptr;
  GMSH(gmshModelGetType)(dim, tag, &p, &ierr);
  entityType = p != nullptr ? p : "";
  if (p != nullptr) GMSH(gmshFree)(p);
  check(ierr);
}

void model::getValue(int dim, int tag, const std::vector<double>& parametricCoord,
                     std::vector<double>& coord) {
  int ierr = 0;
  std::vector<double> par = parametricCoord;
  double* p = nullptr;
  std::size_t n = 0;
  GMSH(gmshModelGetValue)(dim, tag, par.data(), par.size(), &p, &n, &ierr);
  coord = take(p, n);
  check(ierr);
}

int model::geo::addPoint(double x, double y, double z, double meshSize, int tag) {
  int ierr = 0;
  const int out = GMSH(gmshModelGeoAddPoint)(x, y, z, meshSize, tag, &ierr);
  check(ierr);
  return out;
}

int model::geo::addLine(int startTag, int endTag, int tag) {
  int ierr = 0;
  const int out = GMSH(gmshModelGeoAddLine)(startTag, endTag, tag, &ierr);
  check(ierr);
  return out;
}

int model::geo::addCircleArc(int startTag, int centerTag, int endTag, int tag) {
  int ierr = 0;
  const int out =
      GMSH(gmshModelGeoAddCircleArc)(startTag, centerTag, endTag, tag, 0.0, 0.0, 0.0, &ierr);
  check(ierr);
  return out;
}

namespace {
/// The geo functions that take a list of tags and a tag.
template <class F>
int tags_and_tag(F f, const std::vector<int>& tags, int tag) {
  int ierr = 0;
  std::vector<int> t = tags;
  const int out = f(t.data(), t.size(), tag, &ierr);
  check(ierr);
  return out;
}
}  // namespace

int model::geo::addSpline(const std::vector<int>& pointTags, int tag) {
  return tags_and_tag(GMSH(gmshModelGeoAddSpline), pointTags, tag);
}

int model::geo::addCurveLoop(const std::vector<int>& curveTags, int tag) {
  int ierr = 0;
  std::vector<int> t = curveTags;
  const int out = GMSH(gmshModelGeoAddCurveLoop)(t.data(), t.size(), tag, 0, &ierr);
  check(ierr);
  return out;
}

int model::geo::addPlaneSurface(const std::vector<int>& wireTags, int tag) {
  return tags_and_tag(GMSH(gmshModelGeoAddPlaneSurface), wireTags, tag);
}

int model::geo::addSurfaceFilling(const std::vector<int>& wireTags, int tag) {
  int ierr = 0;
  std::vector<int> t = wireTags;
  const int out = GMSH(gmshModelGeoAddSurfaceFilling)(t.data(), t.size(), tag, -1, &ierr);
  check(ierr);
  return out;
}

int model::geo::addSurfaceLoop(const std::vector<int>& surfaceTags, int tag) {
  return tags_and_tag(GMSH(gmshModelGeoAddSurfaceLoop), surfaceTags, tag);
}

int model::geo::addVolume(const std::vector<int>& shellTags, int tag) {
  return tags_and_tag(GMSH(gmshModelGeoAddVolume), shellTags, tag);
}

void model::geo::synchronize() {
  int ierr = 0;
  GMSH(gmshModelGeoSynchronize)(&ierr);
  check(ierr);
}

void model::mesh::generate(int dim) {
  int ierr = 0;
  GMSH(gmshModelMeshGenerate)(dim, &ierr);
  check(ierr);
}

void model::mesh::getNodes(std::vector<std::size_t>& nodeTags, std::vector<double>& coord,
                           std::vector<double>& parametricCoord, int dim, int tag,
                           bool includeBoundary, bool returnParametricCoord) {
  int ierr = 0;
  std::size_t* t = nullptr;
  double *c = nullptr, *p = nullptr;
  std::size_t nt = 0, nc = 0, np = 0;
  GMSH(gmshModelMeshGetNodes)
  (&t, &nt, &c, &nc, &p, &np, dim, tag, includeBoundary, returnParametricCoord, &ierr);
  nodeTags = take(t, nt);
  coord = take(c, nc);
  parametricCoord = take(p, np);
  check(ierr);
}

void model::mesh::addNodes(int dim, int tag, const std::vector<std::size_t>& nodeTags,
                           const std::vector<double>& coord) {
  int ierr = 0;
  std::vector<std::size_t> t = nodeTags;
  std::vector<double> c = coord;
  GMSH(gmshModelMeshAddNodes)(dim, tag, t.data(), t.size(), c.data(), c.size(), nullptr, 0, &ierr);
  check(ierr);
}

void model::mesh::addElementsByType(int tag, int elementType,
                                    const std::vector<std::size_t>& elementTags,
                                    const std::vector<std::size_t>& nodeTags) {
  int ierr = 0;
  std::vector<std::size_t> e = elementTags, n = nodeTags;
  GMSH(gmshModelMeshAddElementsByType)
  (tag, elementType, e.data(), e.size(), n.data(), n.size(), &ierr);
  check(ierr);
}

void model::mesh::getElements(std::vector<int>& elementTypes,
                              std::vector<std::vector<std::size_t>>& elementTags,
                              std::vector<std::vector<std::size_t>>& nodeTags, int dim, int tag) {
  int ierr = 0;
  int* types = nullptr;
  std::size_t ntypes = 0;
  std::size_t **etags = nullptr, **enodes = nullptr;
  std::size_t *netags = nullptr, *nenodes = nullptr;
  std::size_t nn1 = 0, nn2 = 0;
  GMSH(gmshModelMeshGetElements)
  (&types, &ntypes, &etags, &netags, &nn1, &enodes, &nenodes, &nn2, dim, tag, &ierr);
  elementTypes = take(types, ntypes);
  elementTags.clear();
  nodeTags.clear();
  for (std::size_t i = 0; i < nn1; ++i) elementTags.push_back(take(etags[i], netags[i]));
  for (std::size_t i = 0; i < nn2; ++i) nodeTags.push_back(take(enodes[i], nenodes[i]));
  take(etags, nn1);
  take(enodes, nn2);
  take(netags, nn1);
  take(nenodes, nn2);
  check(ierr);
}

void model::mesh::getElementsByType(int elementType, std::vector<std::size_t>& elementTags,
                                    std::vector<std::size_t>& nodeTags, int tag) {
  int ierr = 0;
  std::size_t *e = nullptr, *n = nullptr;
  std::size_t ne = 0, nn = 0;
  GMSH(gmshModelMeshGetElementsByType)(elementType, &e, &ne, &n, &nn, tag, 0, 1, &ierr);
  elementTags = take(e, ne);
  nodeTags = take(n, nn);
  check(ierr);
}

void model::mesh::setRecombine(int dim, int tag) {
  int ierr = 0;
  GMSH(gmshModelMeshSetRecombine)(dim, tag, &ierr);
  check(ierr);
}

void model::mesh::setTransfiniteCurve(int tag, int numNodes, const std::string& meshType,
                                      double coef) {
  int ierr = 0;
  GMSH(gmshModelMeshSetTransfiniteCurve)(tag, numNodes, meshType.c_str(), coef, &ierr);
  check(ierr);
}

void model::occ::importShapes(const std::string& fileName, vectorpair& outDimTags,
                              bool highestDimOnly) {
  int ierr = 0;
  int* p = nullptr;
  std::size_t n = 0;
  GMSH(gmshModelOccImportShapes)(fileName.c_str(), &p, &n, highestDimOnly, "", &ierr);
  outDimTags = pairs(p, n);
  check(ierr);
}

void model::occ::synchronize() {
  int ierr = 0;
  GMSH(gmshModelOccSynchronize)(&ierr);
  check(ierr);
}

void model::occ::getEntities(vectorpair& dimTags, int dim) {
  int ierr = 0;
  int* p = nullptr;
  std::size_t n = 0;
  GMSH(gmshModelOccGetEntities)(&p, &n, dim, &ierr);
  dimTags = pairs(p, n);
  check(ierr);
}

void model::occ::dilate(const vectorpair& dimTags, double x, double y, double z, double a, double b,
                        double c) {
  int ierr = 0;
  std::vector<int> in = flat(dimTags);
  GMSH(gmshModelOccDilate)(in.data(), in.size(), x, y, z, a, b, c, &ierr);
  check(ierr);
}

void model::occ::getMass(int dim, int tag, double& mass) {
  int ierr = 0;
  GMSH(gmshModelOccGetMass)(dim, tag, &mass, &ierr);
  check(ierr);
}

int model::occ::addPoint(double x, double y, double z, double meshSize, int tag) {
  int ierr = 0;
  const int out = GMSH(gmshModelOccAddPoint)(x, y, z, meshSize, tag, &ierr);
  check(ierr);
  return out;
}

int model::occ::addCylinder(double x, double y, double z, double dx, double dy, double dz, double r,
                            int tag, double angle) {
  int ierr = 0;
  const int out = GMSH(gmshModelOccAddCylinder)(x, y, z, dx, dy, dz, r, tag, angle, &ierr);
  check(ierr);
  return out;
}

int model::occ::addBSpline(const std::vector<int>& pointTags, int tag) {
  int ierr = 0;
  std::vector<int> t = pointTags;
  const int out = GMSH(gmshModelOccAddBSpline)(t.data(), t.size(), tag, 3, nullptr, 0, nullptr, 0,
                                               nullptr, 0, &ierr);
  check(ierr);
  return out;
}

}  // namespace impactfe::geometry::gmsh
