// Parameter commands (APDL_SCRIPTING §A.1–§A.7): `Par = expr`, *SET, *DIM, *DEL, *AFUN, and the
// assignment interface of parameters.h (assign_parameter, assign_vector, read_vector, ...).
#include <fmt/format.h>

#include <algorithm>
#include <cmath>

#include "deck/deck_context.h"

namespace impactfe::deck {

namespace {

/// Names refused as parameters: the convenience labels that a node, element or switch field
/// takes in place of a number (ALL, ON, OFF), and the built-in functions. DOF and force labels
/// (UZ, MZ, ...) are accepted, as MAPDL accepts them (its Programmer's Reference only advises
/// against them): the reader never substitutes a numeric parameter into a label field
/// (DeckReader::label), so D,1,UZ and *GET,..,U,Z keep their labels while a numeric field may
/// use the parameter (vm70 stores *GET,MZ,ELEM,...).
bool reserved_label(const std::string& name) {
  return name == "ALL" || name == "ON" || name == "OFF" || is_builtin_function(name);
}

/// A parameter name given as a target (the Par field is never substituted, §A.2).
std::string checked_name(const DeckReader& r, const Command& c, const std::string& name,
                         const std::string& as_written) {
  if (!is_parameter_name(name))
    r.fail(c, fmt::format("'{}' is not a valid parameter name", as_written));
  if (reserved_label(name))
    r.fail(c, fmt::format("'{}' is a label or function name and cannot be a parameter", name));
  return name;
}

struct Target {
  std::string name;
  bool subscripted = false;
  int s[3] = {1, 1, 1};
  int n_subscripts = 0;
};

Target parse_target(DeckReader& r, const Command& c, const std::string& text) {
  const auto n = split_subscripted_name(text);
  if (!n) r.fail(c, fmt::format("'{}' is not a parameter name or array element", text));
  Target t;
  t.name = checked_name(r, c, n->name, text);
  t.subscripted = n->has_parentheses;
  if (!t.subscripted) return t;
  if (n->subscripts.size() > 3)
    r.fail(c, fmt::format("{}: at most three subscripts, {} given", text, n->subscripts.size()));
  t.n_subscripts = static_cast<int>(n->subscripts.size());
  for (int k = 0; k < t.n_subscripts; ++k) {
    const std::string& sub = n->subscripts[static_cast<std::size_t>(k)];
    if (sub.empty()) r.fail(c, fmt::format("{}: subscript {} is blank", text, k + 1));
    const double v = r.eval(c, sub);
    if (!std::isfinite(v) || std::fabs(v) > 1e9) r.fail(c, fmt::format("{}: bad subscript", text));
    t.s[k] = static_cast<int>(std::lround(v));
  }
  return t;
}

Param& element_owner(DeckReader& r, const Command& c, const Target& t) {
  Param* p = r.params.find(t.name);
  if (p == nullptr) r.fail(c, fmt::format("array {} is not defined (*DIM it first)", t.name));
  if (!p->is_array()) r.fail(c, fmt::format("{} is a scalar parameter, not an array", t.name));
  return *p;
}

void check_range(const DeckReader& r, const Command& c, const std::string& name, const Param& p,
                 int i, int j, int k) {
  if (!p.in_range(i, j, k))
    r.fail(c,
           fmt::format("{}({},{},{}) is out of range: {} is {} {}x{}x{} (subscripts from {})", name,
                       i, j, k, name, param_type_name(p.type), p.imax, p.jmax, p.kmax, p.low()));
}

std::string fit_text(const DeckReader& r, const Command& c, std::string text, std::size_t limit,
                     const char* what) {
  if (text.size() > limit) {
    r.warn(c, fmt::format("'{}' cut to {} characters ({})", text, limit, what));
    text.resize(limit);
  }
  return text;
}

/// Stores the values of `Par = v1,v2,...` / *SET,Par,v1,v2,...: a scalar, or successive array
/// elements down the column (§A.2).
void store_values(DeckReader& r, const Command& c, const Target& t, const std::vector<Value>& v) {
  if (!t.subscripted) {
    if (const Param* p = r.params.find(t.name); p != nullptr && p->is_array())
      r.fail(c, fmt::format("{} is an array: give the element, e.g. {}(1) (or delete it with {} =)",
                            t.name, t.name, t.name));
    if (v.size() > 1)
      r.fail(c, fmt::format("{} values for the scalar {}: a list needs an array element target",
                            v.size(), t.name));
    if (is_text(v[0]))
      r.params.set_text(t.name, fit_text(r, c, std::get<std::string>(v[0]), kMaxTextLength,
                                         "character scalars hold 32"));
    else
      r.params.set(t.name, std::get<double>(v[0]));
    return;
  }
  Param& p = element_owner(r, c, t);
  if (p.type == ParamType::StringArray) {
    // Par(i,j,k) = 'text': the text is written into column j from character i on (the row
    // subscript of a STRING array is a character position, *DIM).
    if (v.size() > 1)
      r.fail(c, fmt::format("{} values for the STRING array {}: one text per assignment", v.size(),
                            t.name));
    if (!is_text(v[0]))
      r.fail(c, fmt::format("{} is a STRING array: give a quoted text, not {}", t.name,
                            format_number(std::get<double>(v[0]))));
    check_range(r, c, t.name, p, t.s[0], t.s[1], t.s[2]);
    std::string& entry = p.texts[p.offset(t.s[0], t.s[1], t.s[2])];
    const auto from = static_cast<std::size_t>(t.s[0] - 1);
    if (entry.size() < from) entry.resize(from, ' ');
    entry = entry.substr(0, from) + std::get<std::string>(v[0]);
    entry =
        fit_text(r, c, entry, static_cast<std::size_t>(p.imax), "the STRING array's length, IMAX");
    return;
  }
  for (std::size_t n = 0; n < v.size(); ++n) {
    const int i = t.s[0] + static_cast<int>(n);
    check_range(r, c, t.name, p, i, t.s[1], t.s[2]);
    const std::size_t at = p.offset(i, t.s[1], t.s[2]);
    if (p.type == ParamType::CharArray) {
      if (!is_text(v[n]))
        r.fail(c, fmt::format("{} is a CHAR array: give a quoted text, not {}", t.name,
                              format_number(std::get<double>(v[n]))));
      p.texts[at] = fit_text(r, c, std::get<std::string>(v[n]), kMaxCharEntryLength,
                             "CHAR array entries hold 8");
    } else {
      if (is_text(v[n]))
        r.fail(c, fmt::format("{} is a numeric {}: '{}' is a text", t.name, param_type_name(p.type),
                              std::get<std::string>(v[n])));
      p.values[at] = std::get<double>(v[n]);
    }
  }
}

void cmd_star_set(DeckReader& r, const Command& c) {
  const Target t = parse_target(r, c, c.text(1));
  std::vector<std::string> texts;
  if (c.assignment) {
    if (!c.blank(2)) texts = split_fields(c.text(2));
  } else {
    for (int k = 2; k <= c.n_fields(); ++k) texts.push_back(c.text(k));
  }
  // Values after the first blank one are ignored; a blank VALUE deletes the parameter.
  for (std::size_t k = 0; k < texts.size(); ++k)
    if (texts[k].empty()) {
      if (k + 1 < texts.size() && !(r.dialect == Dialect::Classic4x && k == 1))
        r.warn(c, fmt::format("values after the blank field {} ignored", k + 2));
      texts.resize(k);
      break;
    }
  if (texts.empty()) {
    r.params.erase(t.name);
    r.scripting.increments.erase(t.name);
    return;
  }
  if (r.dialect == Dialect::Classic4x && !c.assignment && !t.subscripted && texts.size() == 2) {
    // 4x *SET,Par,VALUE,INC: INC is added to Par after each pass of a 4x *DO (APDL_SUBSET §3.29).
    r.params.set(t.name, r.eval(c, texts[0]));
    r.scripting.increments[t.name] = r.eval(c, texts[1]);
    return;
  }
  if (texts.size() > 10)
    r.fail(c, fmt::format("{} values given: at most 10 per command", texts.size()));
  std::vector<Value> values;
  for (const auto& text : texts) {
    const std::string name = to_upper(trim(text));
    if (auto num = parse_fortran_number(text)) {
      values.emplace_back(*num);
    } else if (is_parameter_name(name) && r.params.find(name) == nullptr && !is_local_name(name)) {
      // A = B with B undefined: A takes MAPDL's tiny value 2^-100 (APDL Programmer's Reference
      // §3.1); warned, naming B.
      r.warn(c, fmt::format("parameter '{}' is not defined; {} takes MAPDL's value for an "
                            "undefined parameter, 2^-100 = {:.6g}",
                            name, t.name, kUndefinedParameterValue));
      values.emplace_back(kUndefinedParameterValue);
    } else {
      values.push_back(r.eval_value(c, text));
    }
  }
  store_values(r, c, t, values);
}

void cmd_dim(DeckReader& r, const Command& c) {
  // *DIM,Par,Type,IMAX,JMAX,KMAX,Var1,Var2,Var3,CSYSID
  const auto n = split_subscripted_name(c.text(1));
  if (!n || n->has_parentheses) r.fail(c, fmt::format("'{}' is not an array name", c.text(1)));
  const std::string name = checked_name(r, c, n->name, c.text(1));
  const std::string type_label = r.label(c, 2);
  ParamType type = ParamType::Array;
  if (type_label == "CHAR")
    type = ParamType::CharArray;
  else if (type_label == "TABLE")
    type = ParamType::Table;
  else if (type_label == "STRING")
    type = ParamType::StringArray;
  else if (!type_label.empty() && type_label != "ARRAY")
    r.fail(c,
           fmt::format("array type {} is not supported (ARRAY, CHAR, TABLE, STRING)", type_label));
  int dims[3];
  for (int k = 0; k < 3; ++k) {
    dims[k] = r.integer(c, 3 + k, 1);
    if (dims[k] < 1)
      r.fail(c, fmt::format("field {}: extent {} must be at least 1", 3 + k, dims[k]));
  }
  if (type == ParamType::StringArray) {
    // IMAX of a STRING array is its text length: rounded up to a multiple of 8, at most 248.
    if (dims[0] > kMaxStringArrayLength)
      r.fail(c, fmt::format("field 3: a STRING array holds at most {} characters, not {}",
                            kMaxStringArrayLength, dims[0]));
    dims[0] = (dims[0] + 7) / 8 * 8;
  }
  const long long entries = static_cast<long long>(dims[0] + 1) * (dims[1] + 1) * (dims[2] + 1);
  if (entries > kMaxArrayEntries)
    r.fail(c, fmt::format("{}x{}x{} is too large (at most {} entries)", dims[0], dims[1], dims[2],
                          kMaxArrayEntries));
  if (!c.blank(9) && r.real(c, 9, 0.0) != 0.0)
    r.fail(c,
           "CSYSID: table variables in a local coordinate system are not supported (global "
           "Cartesian only)");
  if (const Param* old = r.params.find(name)) {
    if (old->type == type && old->imax == dims[0] && old->jmax == dims[1] && old->kmax == dims[2])
      return;  // the same array again: kept as it is (§A.7 [A])
    r.fail(c, fmt::format("{} is already defined ({}); delete it first ({} =)", name,
                          param_type_name(old->type), name));
  }
  Param p = Param::array(type, dims[0], dims[1], dims[2]);
  if (type == ParamType::Table)
    for (int k = 0; k < 3; ++k)
      if (!c.blank(6 + k)) p.variables[static_cast<std::size_t>(k)] = r.label(c, 6 + k);
  r.params.define(name, std::move(p));
}

void cmd_del(DeckReader& r, const Command& c) {
  // *DEL,Val1,Val2: a parameter, ALL, or (Val2) every name ending / starting with '_'.
  const std::string what = r.label(c, 1);
  const std::string group = r.label(c, 2);
  std::vector<std::string> names;
  if (what == "ALL" || (what.empty() && (group == "PRM_" || group == "_PRM"))) {
    for (const auto& [name, p] : r.params.all()) {
      const bool ends = !name.empty() && name.back() == '_';
      const bool starts = !name.empty() && name.front() == '_';
      if (what == "ALL" ? !starts : (group == "PRM_" ? ends : starts)) names.push_back(name);
    }
  } else if (!what.empty()) {
    const auto n = split_subscripted_name(c.text(1));
    if (!n || r.params.find(n->name) == nullptr) {
      r.warn(c, fmt::format("parameter '{}' is not defined; nothing deleted", c.text(1)));
      return;
    }
    names.push_back(n->name);
  } else {
    r.fail(c, "give a parameter name, ALL, or ,PRM_ / ,_PRM");
  }
  for (const auto& name : names) {
    r.params.erase(name);
    r.scripting.increments.erase(name);
  }
}

void cmd_afun(DeckReader& r, const Command& c) {
  const std::string l = r.label(c, 1);
  if (l == "DEG")
    r.params.degrees = true;
  else if (l == "RAD" || l.empty())
    r.params.degrees = false;
  else if (l == "STAT")
    r.output.print(fmt::format(" ANGLE UNITS ARE {}", r.params.degrees ? "DEGREES" : "RADIANS"));
  else
    r.fail(c, fmt::format("unknown angle unit '{}' (DEG, RAD or STAT)", c.text(1)));
}

}  // namespace

// ---- the assignment interface ------------------------------------------------------------------

ArrayPosition array_position(DeckReader& r, const Command& c, const std::string& text) {
  const auto n = split_subscripted_name(text);
  if (!n) r.fail(c, fmt::format("'{}' is not an array name or element", text));
  Target t;
  if (n->has_parentheses) {
    t = parse_target(r, c, text);
  } else {
    t.name = n->name;
  }
  ArrayPosition pos;
  pos.name = t.name;
  pos.param = &element_owner(r, c, t);
  pos.i = t.s[0];
  pos.j = t.s[1];
  pos.k = t.s[2];
  check_range(r, c, t.name, *pos.param, pos.i, pos.j, pos.k);
  return pos;
}

void assign_parameter(DeckReader& r, const Command& c, const std::string& target, double value) {
  store_values(r, c, parse_target(r, c, target), {Value(value)});
}

void assign_text_parameter(DeckReader& r, const Command& c, const std::string& target,
                           const std::string& value) {
  store_values(r, c, parse_target(r, c, target), {Value(value)});
}

namespace {
Param& numeric_column(DeckReader& r, const Command& c, const ArrayPosition& pos, std::size_t n,
                      const char* verb) {
  Param& p = *pos.param;
  if (p.is_character_array())
    r.fail(c, fmt::format("{} is a {} array: numbers cannot be {} it", pos.name,
                          param_type_name(p.type), verb));
  const long long room = p.imax - pos.i + 1;
  if (static_cast<long long>(n) > room)
    r.fail(c, fmt::format("{} is too short: {} values from row {}, but it has {} row{}", pos.name,
                          n, pos.i, p.imax, p.imax == 1 ? "" : "s"));
  return p;
}
}  // namespace

void assign_vector(DeckReader& r, const Command& c, const std::string& target,
                   const std::vector<double>& values) {
  // An undefined target is dimensioned to hold the values, as POST26 VGET and *VGET create it.
  if (const auto n = split_subscripted_name(target); n && r.params.find(n->name) == nullptr) {
    const Target t = n->has_parentheses ? parse_target(r, c, target)
                                        : Target{checked_name(r, c, n->name, target)};
    if (t.s[0] < 1 || t.s[1] < 1 || t.s[2] < 1)
      r.fail(c, fmt::format("{}: subscripts start at 1", target));
    const long long rows =
        t.s[0] - 1 + static_cast<long long>(std::max<std::size_t>(values.size(), 1));
    if (rows * t.s[1] * t.s[2] > kMaxArrayEntries)
      r.fail(c, fmt::format("{}: more than {} entries", target, kMaxArrayEntries));
    r.params.define(t.name, Param::array(ParamType::Array, static_cast<int>(rows), t.s[1], t.s[2]));
  }
  const ArrayPosition pos = array_position(r, c, target);
  Param& p = numeric_column(r, c, pos, values.size(), "stored in");
  for (std::size_t n = 0; n < values.size(); ++n)
    p.values[p.offset(pos.i + static_cast<int>(n), pos.j, pos.k)] = values[n];
}

std::vector<double> read_vector(DeckReader& r, const Command& c, const std::string& source,
                                int count) {
  if (count < 0) r.fail(c, "negative number of values");
  const ArrayPosition pos = array_position(r, c, source);
  const Param& p = numeric_column(r, c, pos, static_cast<std::size_t>(count), "read from");
  std::vector<double> out(static_cast<std::size_t>(count));
  for (int n = 0; n < count; ++n)
    out[static_cast<std::size_t>(n)] = p.values[p.offset(pos.i + n, pos.j, pos.k)];
  return out;
}

std::vector<double> array_column(DeckReader& r, const Command& c, int field, const char* what) {
  const std::string text = r.label(c, field);
  const std::string name = trim(text.substr(0, text.find('(')));
  const ParameterInfo info = parameter_info(r, name);
  if (name.empty() || info.type != 1)
    r.fail(c, fmt::format("{} '{}': not a numeric array parameter (*DIM,{},ARRAY,n)", what,
                          c.text(field), name.empty() ? "Par" : name));
  const ArrayPosition first = array_position(r, c, text);
  return read_vector(r, c, text, info.dims[0] - first.i + 1);
}

ParameterInfo parameter_info(DeckReader& r, const std::string& name) {
  ParameterInfo info;
  const Param* p = r.params.find(to_upper(trim(name)));
  if (p == nullptr) return info;
  switch (p->type) {
    case ParamType::Number:
      info.type = 0;
      break;
    case ParamType::Array:
      info.type = 1;
      break;
    case ParamType::Table:
      info.type = 2;
      break;
    case ParamType::Text:
      info.type = 3;
      break;
    case ParamType::CharArray:
    case ParamType::StringArray:
      info.type = 4;
      break;
  }
  if (p->is_array()) info.dims[0] = p->imax, info.dims[1] = p->jmax, info.dims[2] = p->kmax;
  return info;
}

std::pair<int, int> parameter_counts(DeckReader& r) {
  int basic = 0;
  for (const auto& [name, p] : r.params.all())
    if (p.type == ParamType::Number) ++basic;
  return {static_cast<int>(r.params.all().size()), basic};
}

void register_parameter_commands(std::vector<CommandSpec>& t) {
  t.push_back({"*SET", cmd_star_set, kAnywhere});
  t.push_back({"*DIM", cmd_dim, kAnywhere});
  t.push_back({"*DEL", cmd_del, kAnywhere});
  t.push_back({"*AFUN", cmd_afun, kAnywhere});
}

}  // namespace impactfe::deck
