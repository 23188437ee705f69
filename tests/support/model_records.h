#pragma once
/// Test support: element types and element records of a model built in code (unit tests of
/// elements that need a Model, such as the contact pairs).
#include <string>
#include <utility>
#include <vector>

#include "core/model.h"

namespace impactfe::testing {

/// An element type `id` of ANSYS name `name` with KEYOPT(2) and KEYOPT(12) set.
inline ElementType element_type(int id, const char* name, int keyopt2 = 0, int keyopt12 = 0) {
  ElementType et;
  et.id = id;
  et.ansys_name = name;
  et.keyopt[2] = keyopt2;
  et.keyopt[12] = keyopt12;
  return et;
}

/// Element `id` with its attributes; its source location is line 10 + id of `file`.
inline ElementRecord element_record(int id, int type_id, int real, int mat, std::vector<int> nodes,
                                    const std::string& file) {
  ElementRecord r;
  r.id = id;
  r.type = type_id;
  r.real = real;
  r.mat = mat;
  r.nodes = std::move(nodes);
  r.where = SourceLocation{file, 10 + id, "E"};
  return r;
}

}  // namespace impactfe::testing
