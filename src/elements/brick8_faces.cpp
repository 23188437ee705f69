// Faces of the 8-node brick (elements/brick8.h) in MAPDL's numbering and its pressure loads.
#include <fmt/format.h>

#include "core/errors.h"
#include "elements/brick8.h"
#include "elements/cell_topology.h"
#include "elements/face_pressure.h"

namespace impactfe {

namespace {
/// Face k + 1 as corner positions with the outward normal by the right-hand rule, in MAPDL's
/// numbering of the solid elements (SOLID185: 1 J-I-L-K, 2 I-J-N-M, 3 J-K-O-N, 4 K-L-P-O,
/// 5 L-I-M-P, 6 M-N-O-P; face-node order = SFE VALUE1..VALUE4): the hexahedron's faces
/// (elements/cell_topology.h: bottom, top, sides) with the top last and the bottom read from J.
std::vector<std::vector<int>> numbered_brick_faces() {
  const auto& f = cell_topology(VtkCell::Hexahedron).faces;
  return {{f[0][3], f[0][0], f[0][1], f[0][2]}, f[2], f[3], f[4], f[5], f[1]};
}

const std::vector<std::vector<int>>& brick_faces() {
  static const std::vector<std::vector<int>> faces = numbered_brick_faces();
  return faces;
}
}  // namespace

void Brick8::pressure_load(const ElementContext& ctx, int face, const std::array<double, 4>& p,
                           const Eigen::VectorXd& u, Eigen::VectorXd& f) const {
  if (face < 1 || face > 6)
    throw ModelError(fmt::format("element {}: brick face {} does not exist (1..6)", id(), face));
  const auto& corners = brick_faces()[static_cast<std::size_t>(face - 1)];
  const Eigen::Matrix<double, 24, 1> uc = to_corners(u);
  std::array<Vec3, 4> x;
  for (int a = 0; a < 4; ++a) {
    const int c = corners[static_cast<std::size_t>(a)];
    x[static_cast<std::size_t>(a)] = x_[static_cast<std::size_t>(c)];
    if (ctx.large_deflection) x[static_cast<std::size_t>(a)] += uc.segment<3>(3 * c);
  }
  // The face orders above make the normal of the corner order point outward; positive pressure
  // pushes inward.
  std::array<Vec3, 4> fa = bilinear_face_pressure_forces(x, p);
  for (Vec3& fc : fa) fc = -fc;
  f.setZero(n_dofs());
  for (int a = 0; a < 4; ++a) {
    const int c = corners[static_cast<std::size_t>(a)];
    f.segment<3>(3 * corner_to_unique_[static_cast<std::size_t>(c)]) +=
        fa[static_cast<std::size_t>(a)];
  }
}

const std::vector<std::vector<int>>& brick8_faces() {
  return brick_faces();
}

}  // namespace impactfe
