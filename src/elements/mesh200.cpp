// MESH200, MAPDL's mesh-only element (MAPDL Element Reference, MESH200): a line, area or volume
// cell that "contributes nothing to the solution". Archives written after a multi-step meshing
// (TetBeam.cdb, sector.cdb: ET,1,200 beside the solids) define it; MAPDL reads and keeps its
// elements, and so does impactfe: they are stored, selected, listed in components and written
// back by CDWRITE, and they have no degrees of freedom, stiffness, mass or results. KEYOPT(1)
// chooses the cell, and so the number of nodes an element must have.
#include <fmt/format.h>

#include <array>

#include "core/errors.h"
#include "elements/element_registry.h"

namespace impactfe {

namespace {

const std::vector<std::string> kMesh200Results;

/// KEYOPT(1) -> (nodes, cell): 0/1 2-D line with 2/3 nodes, 2/3 3-D line with 2/3 nodes,
/// 4/5 triangle with 3/6, 6/7 quadrilateral with 4/8, 8/9 tetrahedron with 4/10, 10/11 brick
/// with 8/20 nodes (MESH200 input summary).
struct Mesh200Cell {
  int nodes;
  const char* name;
};
constexpr std::array<Mesh200Cell, 12> kMesh200Cells = {{{2, "2-D line"},
                                                        {3, "2-D line with a midside node"},
                                                        {2, "3-D line"},
                                                        {3, "3-D line with a midside node"},
                                                        {3, "triangle"},
                                                        {6, "triangle with midside nodes"},
                                                        {4, "quadrilateral"},
                                                        {8, "quadrilateral with midside nodes"},
                                                        {4, "tetrahedron"},
                                                        {10, "tetrahedron with midside nodes"},
                                                        {8, "brick"},
                                                        {20, "brick with midside nodes"}}};

class MeshOnly final : public Element {
 public:
  explicit MeshOnly(int id) : Element(id) {}
  const char* family() const override { return "MeshOnly"; }
  const std::vector<DofKey>& dofs() const override { return dofs_; }
  bool is_nonlinear(const ElementContext&) const override { return false; }
  void tangent(const ElementContext&, const Eigen::VectorXd&, Eigen::MatrixXd& K,
               Eigen::VectorXd& f_int) const override {
    K.resize(0, 0);
    f_int.resize(0);
  }
  void mass(const ElementContext&, Eigen::MatrixXd& M) const override { M.resize(0, 0); }
  const std::vector<std::string>& result_names() const override { return kMesh200Results; }
  void results(const ElementContext&, const Eigen::VectorXd&, const Eigen::VectorXd&,
               ElementResultValues& out) const override {
    out.clear();
  }

 private:
  std::vector<DofKey> dofs_;  // none: the element joins no degree of freedom
};

std::unique_ptr<Element> make_mesh_only(const ElementBuildContext& ctx,
                                        const ElementRecord& record) {
  const auto type = ctx.model.element_types.find(record.type);
  if (type == ctx.model.element_types.end())
    throw InputError(record.where, fmt::format("element {}: element type {} is not defined",
                                               record.id, record.type));
  const int shape = type->second.key(1);
  if (shape < 0 || shape >= static_cast<int>(kMesh200Cells.size()))
    throw InputError(record.where,
                     fmt::format("element {} (MESH200): KEYOPT(1) = {} is not a MESH200 shape "
                                 "(0 to 11)",
                                 record.id, shape));
  const Mesh200Cell& cell = kMesh200Cells[static_cast<std::size_t>(shape)];
  int given = static_cast<int>(record.nodes.size());
  while (given > 0 && record.nodes[static_cast<std::size_t>(given - 1)] == 0) --given;
  if (given != cell.nodes)
    throw InputError(record.where,
                     fmt::format("element {} (MESH200, KEYOPT(1) = {}: {}) needs {} nodes, {} "
                                 "given",
                                 record.id, shape, cell.name, cell.nodes, given));
  return std::make_unique<MeshOnly>(record.id);
}

// The cell varies with KEYOPT(1): the element is stored as its list of 2 to 20 nodes (a set of
// points to the pictures), checked against the shape when the model is built.
const ElementRegistration kMesh200{{.name = "MESH200",
                                    .number = 200,
                                    .family = "MeshOnly",
                                    .n_nodes = 2,
                                    .n_optional_nodes = 18,
                                    .real_constants = RealConstantUse::None,
                                    .vtk_cell = VtkCell::PolyVertex,
                                    .role = ShapeRole::Point,
                                    .result_names = kMesh200Results,
                                    .note = "MESH200 is mesh-only: its elements are kept and "
                                            "written back, and contribute nothing to the "
                                            "solution",
                                    .create = make_mesh_only}};

}  // namespace

}  // namespace impactfe
