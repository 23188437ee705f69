#pragma once
/// Deck-reading state of the PREP7 model-building commands (APDL_MODELING §3-§6) that is not part
/// of the model itself: the attribute pointers that E takes (TYPE, REAL, MAT, SECNUM, ESYS), the
/// targets of the continuation commands (RMORE, SECDATA, TBDATA), the MPTEMP table and the
/// generation memory. Written by the PREP7 handlers; /CLEAR replaces it with a new one.
#include <cstddef>
#include <optional>
#include <string>
#include <utility>
#include <vector>

#include "core/model.h"

namespace impactfe::deck {

struct ModelingState {
  /// The state a new database starts with: SECNUM 1 in the modern dialect (MAPDL's default
  /// section pointer), 0 in 4x (real constants only).
  static ModelingState initial(Dialect dialect) {
    ModelingState s;
    s.current_secnum = dialect == Dialect::Modern ? 1 : 0;
    return s;
  }

  // Attribute pointers (TYPE, REAL, MAT, SECNUM, ESYS) of the elements E defines next.
  int current_type = 1;
  int current_real = 1;
  int current_mat = 1;
  int current_secnum = 0;
  bool secnum_given = false;  // SECNUM issued
  int esys = 0;
  /// TSHAP shape of the TARGE170 elements that E/EN define next ("" = from the node count).
  std::string target_shape;

  // Targets of the continuation commands.
  int last_real_set = 0;       // RMORE
  int last_section = 0;        // SECDATA
  std::vector<double> mptemp;  // MPTEMP temperatures (positions 1..)
  /// (MAT, Lab) of the last TB command and the index of its current temperature (TBTEMP).
  std::optional<std::pair<int, std::string>> table;
  std::size_t table_temperature = 0;
  /// The equation of the last `CE,R5.0,DEFI` of a CDB archive and how many of its terms the
  /// `CE,R5.0,NODE` records after it have still to give.
  int archive_equation = 0;
  int archive_terms_left = 0;

  // Generation memory.
  std::vector<int> defined_by_n;   // nodes defined by N, in order (FILL defaults)
  int moved_nodes_checked = 0;     // nodes N moved and looked up in the elements (a few)
  std::vector<int> element_order;  // element ids in creation order (EGEN negative IEL1)
  /// EMORE target: the element last defined by E / EN and the position of its next node.
  int emore_element = 0;
  int emore_position = 0;
};

}  // namespace impactfe::deck
