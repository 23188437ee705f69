// Get functions and *GET items answered from the model (APDL_MODELING §10.1, §10.3;
// APDL_SCRIPTING §B), and the tables other groups extend.
#include "deck/get_hooks.h"

#include <fmt/format.h>

#include <algorithm>
#include <cmath>
#include <limits>

#include "deck/deck_context.h"
#include "deck/get_functions.h"

namespace impactfe::deck {

// ---- selection as the get functions see it
// -------------------------------------------------------

bool DeckReader::node_selected(int id) const {
  return model.nodes.count(id) != 0 && model.selection.nodes.selected(id);
}

bool DeckReader::element_selected(int id) const {
  return model.elements.count(id) != 0 && model.selection.elements.selected(id);
}

bool DeckReader::FunctionBridge::call(const std::string& name, const std::vector<double>& args,
                                      double& result) const {
  const GetFunctionSpec* f = find_get_function(name);
  if (f == nullptr) return false;
  const int n = static_cast<int>(args.size());
  if (n < f->min_args || n > f->max_args) {
    if (f->min_args == f->max_args)
      throw ExpressionError(fmt::format("{} takes {} argument{}, {} given", name, f->min_args,
                                        f->min_args == 1 ? "" : "s", n));
    throw ExpressionError(
        fmt::format("{} takes {} to {} arguments, {} given", name, f->min_args, f->max_args, n));
  }
  result = f->evaluate(*reader, args);
  return true;
}

namespace {

int id_of(double v, const char* what) {
  if (!std::isfinite(v) || std::fabs(v) > 2e9)
    throw ExpressionError(fmt::format("bad {} number", what));
  return static_cast<int>(std::lround(v));
}

const Node& node_arg(const DeckReader& r, double v, const char* f) {
  const int id = id_of(v, "node");
  const auto it = r.model.nodes.find(id);
  if (it == r.model.nodes.end())
    throw ExpressionError(fmt::format("{}({}): node {} is not defined", f, id, id));
  return it->second;
}

const ElementRecord& element_arg(const DeckReader& r, double v, const char* f) {
  const int id = id_of(v, "element");
  const auto it = r.model.elements.find(id);
  if (it == r.model.elements.end())
    throw ExpressionError(fmt::format("{}({}): element {} is not defined", f, id, id));
  return it->second;
}

/// Centroid of an element from its distinct selected nodes (§10.3: CENTRX..Z); the element's
/// nodes when none is selected.
Vec3 centroid(const DeckReader& r, const ElementRecord& e) {
  std::vector<int> ids;
  for (int n : e.nodes)
    if (std::find(ids.begin(), ids.end(), n) == ids.end() && r.node_selected(n)) ids.push_back(n);
  if (ids.empty())
    for (int n : e.nodes)
      if (std::find(ids.begin(), ids.end(), n) == ids.end()) ids.push_back(n);
  Vec3 c = Vec3::Zero();
  for (int n : ids) c += r.model.node(n).x;
  return ids.empty() ? c : Vec3(c / static_cast<double>(ids.size()));
}

/// The selected node nearest `p` (lowest number on ties), excluding `skip`; 0 when none.
int nearest_node(const DeckReader& r, const Vec3& p, int skip) {
  int best = 0;
  double best_d = std::numeric_limits<double>::infinity();
  for (const auto& [id, node] : r.model.nodes) {
    if (id == skip || !r.node_selected(id)) continue;
    const double d = (node.x - p).squaredNorm();
    if (d < best_d) {
      best_d = d;
      best = id;
    }
  }
  return best;
}

template <class Map, class Selected>
int next_selected(const Map& m, int from, Selected selected, bool higher) {
  if (higher) {
    for (auto it = m.upper_bound(from); it != m.end(); ++it)
      if (selected(it->first)) return it->first;
  } else {
    for (auto it = std::make_reverse_iterator(m.lower_bound(from)); it != m.rend(); ++it)
      if (selected(it->first)) return it->first;
  }
  return 0;
}

double f_nx(DeckReader& r, const std::vector<double>& a) {
  return node_arg(r, a[0], "NX").x(0);
}
double f_ny(DeckReader& r, const std::vector<double>& a) {
  return node_arg(r, a[0], "NY").x(1);
}
double f_nz(DeckReader& r, const std::vector<double>& a) {
  return node_arg(r, a[0], "NZ").x(2);
}

double f_node(DeckReader& r, const std::vector<double>& a) {
  const Vec3 p(a[0], a.size() > 1 ? a[1] : 0.0, a.size() > 2 ? a[2] : 0.0);
  return nearest_node(r, p, 0);
}

double f_nnear(DeckReader& r, const std::vector<double>& a) {
  const Node& n = node_arg(r, a[0], "NNEAR");
  return nearest_node(r, n.x, n.id);
}

double f_enearn(DeckReader& r, const std::vector<double>& a) {
  const Node& n = node_arg(r, a[0], "ENEARN");
  int best = 0;
  double best_d = std::numeric_limits<double>::infinity();
  for (const auto& [id, e] : r.model.elements) {
    if (!r.element_selected(id)) continue;
    const double d = (centroid(r, e) - n.x).squaredNorm();
    if (d < best_d) {
      best_d = d;
      best = id;
    }
  }
  return best;
}

double f_distnd(DeckReader& r, const std::vector<double>& a) {
  return (node_arg(r, a[0], "DISTND").x - node_arg(r, a[1], "DISTND").x).norm();
}

double f_centrx(DeckReader& r, const std::vector<double>& a) {
  return centroid(r, element_arg(r, a[0], "CENTRX"))(0);
}
double f_centry(DeckReader& r, const std::vector<double>& a) {
  return centroid(r, element_arg(r, a[0], "CENTRY"))(1);
}
double f_centrz(DeckReader& r, const std::vector<double>& a) {
  return centroid(r, element_arg(r, a[0], "CENTRZ"))(2);
}

double f_nelem(DeckReader& r, const std::vector<double>& a) {
  const ElementRecord& e = element_arg(r, a[0], "NELEM");
  const int pos = id_of(a[1], "position");
  return pos >= 1 && pos <= static_cast<int>(e.nodes.size())
             ? e.nodes[static_cast<std::size_t>(pos - 1)]
             : 0.0;
}

double f_nsel(DeckReader& r, const std::vector<double>& a) {
  const int id = id_of(a[0], "node");
  return r.model.nodes.count(id) == 0 ? 0.0 : (r.node_selected(id) ? 1.0 : -1.0);
}

double f_esel(DeckReader& r, const std::vector<double>& a) {
  const int id = id_of(a[0], "element");
  return r.model.elements.count(id) == 0 ? 0.0 : (r.element_selected(id) ? 1.0 : -1.0);
}

double f_ndnext(DeckReader& r, const std::vector<double>& a) {
  return next_selected(
      r.model.nodes, id_of(a[0], "node"), [&](int id) { return r.node_selected(id); }, true);
}

double f_elnext(DeckReader& r, const std::vector<double>& a) {
  return next_selected(
      r.model.elements, id_of(a[0], "element"), [&](int id) { return r.element_selected(id); },
      true);
}

// ---- *GET items from the model ------------------------------------------------------------------

int axis_of(const std::string& l) {
  return l == "X" ? 0 : l == "Y" ? 1 : l == "Z" ? 2 : -1;
}

std::optional<Value> node_items(DeckReader& r, const Command& c, const GetItem& q) {
  if (q.entity != "NODE") return std::nullopt;
  const int id = static_cast<int>(std::lround(q.entnum));
  auto sel = [&](int n) { return r.node_selected(n); };
  if (q.item1 == "COUNT") {
    double n = 0;
    for (const auto& [nid, node] : r.model.nodes) n += r.node_selected(nid) ? 1 : 0;
    return n;
  }
  if (q.item1 == "NUM" && (q.it1num == "MAX" || q.it1num == "MIN")) {
    int found = 0;
    for (const auto& [nid, node] : r.model.nodes)
      if (r.node_selected(nid) && (found == 0 || q.it1num == "MAX")) found = nid;
    return static_cast<double>(found);
  }
  if (q.item1 == "NXTH") return static_cast<double>(next_selected(r.model.nodes, id, sel, true));
  if (q.item1 == "NXTL") return static_cast<double>(next_selected(r.model.nodes, id, sel, false));
  if (q.item1 == "NSEL") return f_nsel(r, {q.entnum});
  if (q.item1 != "LOC") return std::nullopt;
  const int axis = axis_of(q.it1num);
  if (axis < 0) r.fail(c, fmt::format("NODE,{},LOC: component '{}' (X, Y or Z)", id, q.it1num));
  const auto it = r.model.nodes.find(id);
  if (it == r.model.nodes.end()) {
    if (q.missing_is_zero) return 0.0;
    r.fail(c, fmt::format("node {} is not defined", id));
  }
  return it->second.x(axis);
}

std::optional<Value> element_items(DeckReader& r, const Command& c, const GetItem& q) {
  if (q.entity != "ELEM") return std::nullopt;
  const int id = static_cast<int>(std::lround(q.entnum));
  auto sel = [&](int e) { return r.element_selected(e); };
  if (q.item1 == "COUNT") {
    double n = 0;
    for (const auto& [eid, e] : r.model.elements) n += r.element_selected(eid) ? 1 : 0;
    return n;
  }
  if (q.item1 == "NUM" && (q.it1num == "MAX" || q.it1num == "MIN")) {
    int found = 0;
    for (const auto& [eid, e] : r.model.elements)
      if (r.element_selected(eid) && (found == 0 || q.it1num == "MAX")) found = eid;
    return static_cast<double>(found);
  }
  if (q.item1 == "NXTH") return static_cast<double>(next_selected(r.model.elements, id, sel, true));
  if (q.item1 == "NXTL")
    return static_cast<double>(next_selected(r.model.elements, id, sel, false));
  if (q.item1 == "ESEL") return f_esel(r, {q.entnum});
  if (q.item1 != "NODE" && q.item1 != "ATTR" && q.item1 != "CENT") return std::nullopt;
  const auto it = r.model.elements.find(id);
  if (it == r.model.elements.end()) {
    if (q.missing_is_zero) return 0.0;
    r.fail(c, fmt::format("element {} is not defined", id));
  }
  const ElementRecord& e = it->second;
  if (q.item1 == "NODE") {
    const int pos = static_cast<int>(std::lround(r.eval(c, q.it1num.empty() ? "1" : q.it1num)));
    return pos >= 1 && pos <= static_cast<int>(e.nodes.size())
               ? static_cast<double>(e.nodes[static_cast<std::size_t>(pos - 1)])
               : 0.0;
  }
  if (q.item1 == "CENT") {
    const int axis = axis_of(q.it1num);
    if (axis < 0) r.fail(c, fmt::format("ELEM,{},CENT: component '{}' (X, Y or Z)", id, q.it1num));
    return centroid(r, e)(axis);
  }
  if (q.it1num == "MAT") return static_cast<double>(e.mat);
  if (q.it1num == "TYPE") return static_cast<double>(e.type);
  if (q.it1num == "REAL") return static_cast<double>(e.real);
  if (q.it1num == "SECN") return static_cast<double>(e.secnum);
  return std::nullopt;  // ESYS, ENAM: get_command.cpp's items
}

std::optional<Value> parm_items(DeckReader& r, const Command& c, const GetItem& q) {
  if (q.entity != "PARM") return std::nullopt;
  if (q.entname.empty() && (q.item1 == "MAX" || q.item1 == "BASIC")) {
    double n = 0;
    for (const auto& [name, p] : r.params.all())
      n += q.item1 == "MAX" || p.type == ParamType::Number ? 1 : 0;
    return n;
  }
  const Param* p = r.params.find(q.entname);
  if (q.item1 == "TYPE") {
    if (p == nullptr) return -1.0;
    switch (p->type) {
      case ParamType::Number:
        return 0.0;
      case ParamType::Array:
        return 1.0;
      case ParamType::Table:
        return 2.0;
      case ParamType::Text:
        return 3.0;
      case ParamType::CharArray:
      case ParamType::StringArray:
        return 4.0;
    }
  }
  if (q.item1 == "DIM") {
    if (p == nullptr) r.fail(c, fmt::format("parameter {} is not defined", q.entname));
    const int axis = axis_of(q.it1num.empty() ? "X" : q.it1num);
    if (axis < 0)
      r.fail(c, fmt::format("PARM,{},DIM: component '{}' (X, Y or Z)", q.entname, q.it1num));
    if (!p->is_array()) return 1.0;
    return static_cast<double>(axis == 0 ? p->imax : axis == 1 ? p->jmax : p->kmax);
  }
  if (q.item1 == "VALUE") {
    if (p == nullptr || p->type == ParamType::Number) return p ? Value(p->number) : Value(0.0);
    if (p->type == ParamType::Text) return p->text;
  }
  return std::nullopt;
}

}  // namespace

void register_model_get_functions(std::vector<GetFunctionSpec>& t) {
  t.push_back({"NX", 1, 1, f_nx});
  t.push_back({"NY", 1, 1, f_ny});
  t.push_back({"NZ", 1, 1, f_nz});
  t.push_back({"NODE", 1, 3, f_node});
  t.push_back({"NNEAR", 1, 1, f_nnear});
  t.push_back({"ENEARN", 1, 1, f_enearn});
  t.push_back({"DISTND", 2, 2, f_distnd});
  t.push_back({"CENTRX", 1, 1, f_centrx});
  t.push_back({"CENTRY", 1, 1, f_centry});
  t.push_back({"CENTRZ", 1, 1, f_centrz});
  t.push_back({"NELEM", 2, 2, f_nelem});
  t.push_back({"NSEL", 1, 1, f_nsel});
  t.push_back({"ESEL", 1, 1, f_esel});
  t.push_back({"NDNEXT", 1, 1, f_ndnext});
  t.push_back({"ELNEXT", 1, 1, f_elnext});
}

const std::vector<GetFunctionSpec>& get_function_table() {
  static const std::vector<GetFunctionSpec> table = [] {
    std::vector<GetFunctionSpec> t;
    register_model_get_functions(t);
    register_results_get_functions(t);  // get_functions.cpp
    return t;
  }();
  return table;
}

const GetFunctionSpec* find_get_function(const std::string& name) {
  const auto& t = get_function_table();
  for (auto it = t.rbegin(); it != t.rend(); ++it)
    if (name == it->name) return &*it;
  return nullptr;
}

void register_model_get_items(std::vector<GetItemProvider>& t) {
  t.push_back(node_items);
  t.push_back(element_items);
  t.push_back(parm_items);
}

const std::vector<GetItemProvider>& get_item_providers() {
  static const std::vector<GetItemProvider> table = [] {
    std::vector<GetItemProvider> t;
    register_results_get_items(t);  // get_command.cpp; tried after the model items
    register_model_get_items(t);
    return t;
  }();
  return table;
}

const std::vector<PutItemProvider>& put_item_providers() {
  static const std::vector<PutItemProvider> table;  // results items register here
  return table;
}

namespace {
std::string describe(const GetItem& q) {
  std::string s = q.entity + "," + (q.entname.empty() ? format_number(q.entnum) : q.entname);
  for (const std::string* f : {&q.item1, &q.it1num, &q.item2, &q.it2num}) s += "," + *f;
  while (!s.empty() && s.back() == ',') s.pop_back();
  return s;
}
}  // namespace

Value get_item(DeckReader& r, const Command& c, const GetItem& q) {
  const auto& t = get_item_providers();
  for (auto it = t.rbegin(); it != t.rend(); ++it)
    if (auto v = (*it)(r, c, q)) return *v;
  r.fail(c, fmt::format("{} is not an item this program can get", describe(q)));
}

void put_item(DeckReader& r, const Command& c, const GetItem& q, double value) {
  const auto& t = put_item_providers();
  for (auto it = t.rbegin(); it != t.rend(); ++it)
    if ((*it)(r, c, q, value)) return;
  r.fail(c, fmt::format("{} cannot be stored into (no item of the database takes *VPUT values)",
                        describe(q)));
}

}  // namespace impactfe::deck
