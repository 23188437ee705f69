#pragma once
/// The element registry: every element type registers itself once, beside its class, with what
/// the rest of the program needs to know about it (ANSYS names, node count, required data, its
/// cell and shape role, faces for surface loads, result items, status, plasticity). The deck
/// reader's validation, the supported-type list of error messages, the mesher, the VTK export,
/// the POST1 pictures, the report and the superelement file take this from here; nothing
/// outside src/elements tests an element's name or family.
///
/// Registration is one line in the element's .cpp:
///   const ElementRegistration kCombin14{{.name = "COMBIN14", .number = 14, ..., .create = ...}};
#include <functional>
#include <memory>
#include <optional>
#include <string>
#include <vector>

#include "elements/cell_topology.h"
#include "elements/element.h"
#include "elements/explicit_kernel.h"

namespace impactfe {

/// Whether an element type reads a real-constant set (R).
enum class RealConstantUse {
  None,           // never (bricks)
  Required,       // always (springs, masses, gaps)
  UnlessSection,  // unless the element's SECNUM names a section of an accepted type (LINK180)
  Optional,       // read when the element's REAL set exists (COMBI165)
};

/// What an element is to the parts of the program that draw, mesh or connect it (the report's
/// bodies, the mesher's element dimension, ESURF).
enum class ShapeRole {
  Solid,         // a volume of material (bricks)
  Plane,         // an area of material in the X-Y plane: plane stress/strain, axisymmetric
  Shell,         // a surface of material with a thickness
  Line,          // a spar, beam or spring between two nodes
  Point,         // a mass at a node
  Gap,           // acts between two bodies at a node pair (COMBIN40, CONTA178): joins no bodies
  Contact,       // the contact side of a surface-to-surface pair (CONTA174 faces, CONTA175 nodes)
  Target,        // the target side (TARGE170 facets and pilot)
  Superelement,  // a reduced matrix on master nodes (MATRIX50)
};

using ElementFactory =
    std::function<std::unique_ptr<Element>(const ElementBuildContext&, const ElementRecord&)>;

/// How an MAPDL output item of ETABLE / ESOL / *GET ELEM / PRESOL (Item,Comp such as SMISC,1,
/// LS,1 or S,EQV) reads a stored result of the element: value = stored `name` + offset.
struct ResultSequence {
  std::string item;  // SMISC, NMISC, LS, LEPEL, S, EPEL (upper case)
  std::string comp;  // "1", "X", "EQV" (upper case)
  std::string name;  // stored result name (one of result_names)
  double offset = 0.0;
};

/// What one element type (one ANSYS name) tells the rest of the program.
struct ElementTypeDescriptor {
  std::string name;    // ANSYS name, upper case: "LINK8"
  int number = 0;      // ANSYS 4.2 type number (ET,1,8); 0 when the type has none
  std::string family;  // descriptive family of the element class: "Spar"
  /// Nodes E must give: from `min_nodes` to `n_nodes + n_optional_nodes`. Missing corner nodes
  /// between min_nodes and n_nodes repeat the last given node (a 3-node SHELL63 is a triangle,
  /// K repeated as L); optional nodes beyond n_nodes (a beam's orientation node) may be absent.
  int n_nodes = 0;
  int min_nodes = 0;  // 0: same as n_nodes
  int n_optional_nodes = 0;
  /// Defined by a file, not by nodes (MATRIX50: SE,File or 4x E,id,unit).
  bool defined_by_file = false;
  RealConstantUse real_constants = RealConstantUse::None;
  bool needs_material = false;
  /// SECTYPE types an element of this type may reference through SECNUM ("LINK", "SHELL").
  std::vector<std::string> section_types;
  /// The reference cell of the element's nodes (cell_topology.h: corners, faces, edges).
  VtkCell vtk_cell = VtkCell::PolyVertex;
  ShapeRole role = ShapeRole::Point;
  /// Result item names, in the order Element::results() returns them.
  std::vector<std::string> result_names;
  /// MAPDL item/sequence numbers of the stored results (APDL_SCRIPTING §D.6).
  std::vector<ResultSequence> result_sequences;
  /// True when elements of this type may carry a status (gap open/closed, slider).
  bool has_status = false;
  /// True when ESYS > 0 (ElementRecord::esys) orients the element's axes; a SOLVE refuses it
  /// on the other types (esys_refusal).
  bool esys_axes = false;
  /// True when the element applies a TB plasticity law of its material (BISO, BKIN, MISO:
  /// materials/j2_plasticity.h); a SOLVE refuses such a material on other types.
  bool plasticity = false;
  /// Faces for surface loads (SF, SFE; APDL_MODELING §5.1): faces[k] lists the node positions
  /// (0-based in the element's node list) of face k + 1, in the element's face-node order (the
  /// order of SFE VALUE1..VALUE4). Empty: the type takes no surface loads.
  std::vector<std::vector<int>> faces;
  /// Faces that SF (by selected nodes) may load: the first `sf_faces` ones (shells: face 1).
  int sf_faces = 0;
  /// KEYOPT(k) = 1 (k = this number; 0: none) makes the type the 6-node triangle I J K L M N
  /// (L M N midside nodes of I-J J-K K-I) of a quadratic quadrilateral cell: E stores it as
  /// the quadrilateral with K = L = O (I J K K L M K N), the one form of the rest of the program.
  int triangle_form_keyopt = 0;
  /// Logged when ET defines the type (e.g. a kernel substitution worth knowing about).
  std::string note;
  ElementFactory create;
  /// Explicit dynamics: builds the elements of this type of one run as a set (explicit_kernel.h).
  /// A type with it and no implicit kernel (SOLID164) runs only in an explicit analysis; an
  /// analysis whose elements all have it runs explicit (docs/explicit_dynamics.md).
  ExplicitSetFactory explicit_set = nullptr;

  const CellTopology& topology() const { return cell_topology(vtk_cell); }
  int max_nodes() const { return n_nodes + n_optional_nodes; }
  int least_nodes() const { return min_nodes > 0 ? min_nodes : n_nodes; }
  bool accepts_section(const std::string& type) const;
};

/// Adds a type to the registry. A second registration under the same name or number is a
/// programming error (InternalError).
void register_element_type(ElementTypeDescriptor descriptor);

/// Registers at static-initialisation time: one such object per element type, in the element's
/// .cpp (or in a test, for a test-only element).
struct ElementRegistration {
  explicit ElementRegistration(ElementTypeDescriptor descriptor);
};

/// Looks up an ET name or 4.2 number (case-insensitive: "link8", "8"); nullptr when unknown.
const ElementTypeDescriptor* find_element_type(const std::string& name_or_number);
/// The descriptor of a defined element type (InternalError when the name is not registered:
/// ET only stores registered names).
const ElementTypeDescriptor& element_type_descriptor(const ElementType& type);
/// All registered types, ordered by name.
std::vector<const ElementTypeDescriptor*> registered_element_types();
/// "COMBIN14 COMBIN40 LINK1 ..." for error messages.
std::string supported_element_type_names();
/// Why an element's ESYS cannot be carried out (empty when it can: ESYS 0, or a defined local
/// system on a type with esys_axes).
std::string esys_refusal(const Model& model, const ElementRecord& record);
/// The global directions of the axes of local system `esys` at the point `x` (columns; a
/// curvilinear system's at that point). Precondition: esys_refusal is empty.
Eigen::Matrix3d esys_axes_at(const Model& model, int esys, const Eigen::Vector3d& x);
/// The stored result that MAPDL's Item,Comp of an element of this type reads (nullopt when the
/// element has none); Item may also be a stored result name itself (Comp blank).
std::optional<ResultSequence> find_result_sequence(const ElementTypeDescriptor& type,
                                                   const std::string& item,
                                                   const std::string& comp);

}  // namespace impactfe
