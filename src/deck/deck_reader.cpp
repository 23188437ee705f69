// Deck reader entry points, dialect detection and the field helpers shared by the handlers
// (the executor is control_flow.cpp).
#include "deck/deck_reader.h"

#include <fmt/format.h>

#include <algorithm>
#include <cctype>
#include <cmath>
#include <filesystem>
#include <fstream>
#include <set>
#include <sstream>

#include "core/files.h"
#include "deck/deck_context.h"
#include "deck/post_support.h"
#include "elements/element_registry.h"

namespace impactfe {

namespace deck {

namespace {

std::string canonical_or_self(const std::string& path) {
  std::error_code ec;
  const auto canonical = std::filesystem::weakly_canonical(path, ec);
  return ec ? path : canonical.string();
}

/// Spec §2.3: 4x when the deck uses KAN, KAY, ITER, LWRITE, AFWRITE, /INPUT,27, /STRESS or
/// *BEGIN (a 4x *DO names a *BEGIN block, so *BEGIN already decides). Included files count,
/// each scanned once (`scanned`): a deck that includes itself, or files that include each other,
/// are read once each, not once per path through the inclusions (a deck including itself three
/// times was read 3^20 times). Files that cannot be read are left to the executor to report.
bool uses_4x(const std::vector<RawCommand>& cmds, const std::string& path,
             std::set<std::string>& scanned) {
  for (const auto& c : cmds) {
    const std::string& n = c.name;
    if (n == "KAN" || n == "KAY" || n == "ITER" || n == "LWRITE" || n == "AFWRITE" ||
        n == "/STRESS" || n == "*BEGIN")
      return true;
    if (n == "/INPUT" && !c.fields.empty()) {
      if (trim(c.fields[0]) == "27") return true;
      const std::string inc =
          resolve_input(path, c.fields[0], c.fields.size() > 1 ? c.fields[1] : std::string());
      if (!scanned.insert(canonical_or_self(inc)).second) continue;
      std::optional<std::string> text;
      try {
        text = read_file(inc, ReadLimits::text());
      } catch (const OversizedFileError&) {
        continue;
      }
      if (text && uses_4x(lex_text(*text, inc, Dialect::Modern), inc, scanned)) return true;
    }
  }
  return false;
}

}  // namespace

// ---- Command --------------------------------------------------------------------------------

const std::string& Command::text(int i) const {
  static const std::string empty;
  if (i < 1 || i > n_fields()) return empty;
  return fields[static_cast<std::size_t>(i - 1)];
}

int Command::last_given() const {
  for (int i = n_fields(); i >= 1; --i)
    if (!blank(i)) return i;
  return 0;
}

// ---- DeckReader -------------------------------------------------------------------------------

DeckReader::DeckReader(const DeckOptions& opts, Dialect d, const std::string& jobname)
    : options(opts), model(job.model), dialect(d), output(opts.output) {
  functions_.reader = this;
  model.dialect = d;
  model.jobname = jobname;
  jobname_from_option = !opts.jobname.empty();
  // 4x decks integrate with Houbolt (the only 4.2 integrator); modern decks default to Newmark.
  model.options.integrator =
      d == Dialect::Classic4x ? IntegratorKind::Houbolt : IntegratorKind::Newmark;
  // MAPDL elements carry SECNUM 1 unless changed; 4x had no sections.
  modeling = ModelingState::initial(d);
}

void DeckReader::fail(const Command& c, const std::string& message) const {
  throw InputError(c.where, message);
}

void DeckReader::warn(const Command& c, const std::string& message) const {
  Log::warn("{}:{}: {}: {}", c.where.file, c.where.line, c.where.command, message);
}

void DeckReader::ignore(const Command& c) {
  const CommandSpec* spec = find_command(c.name);
  IMPACTFE_CHECK(spec != nullptr && spec->ignored != nullptr,
                 "an ignored command needs its reason in the command table");
  job.ignored_commands.push_back(fmt::format("{}:{}: {}", c.where.file, c.where.line, c.name));
  Log::info("{}:{}: {}: accepted and ignored: {}", c.where.file, c.where.line, c.name,
            spec->ignored);
}

std::optional<double> DeckReader::opt_real(const Command& c, int i) const {
  const std::string& t = c.text(i);
  if (t.empty()) return std::nullopt;
  std::optional<double> value = parse_fortran_number(t);
  try {
    if (!value) {
      const Value v = evaluate_value(t, params, &functions_);
      if (is_text(v))
        fail(c, fmt::format("field {}: a number is needed, not the text '{}'", i,
                            std::get<std::string>(v)));
      value = std::get<double>(v);
    }
  } catch (const ExpressionError& e) {
    // A numeric field that is only the name of an undefined parameter takes MAPDL's "tiny"
    // value 2^-100 (APDL Programmer's Reference §3.6: a parameter used in a numeric field but
    // not defined is substituted by 2^-100, usually without warning). impactfe warns, naming the
    // parameter; a name inside an expression (LEN*WIDTH) stays an error.
    if (is_parameter_name(t) && params.find(to_upper(t)) == nullptr) {
      warn(c, fmt::format("field {}: parameter '{}' is not defined; it takes MAPDL's value for "
                          "an undefined parameter, 2^-100 = {:.6g}",
                          i, to_upper(t), kUndefinedParameterValue));
      return kUndefinedParameterValue;
    }
    bool letters = false;
    for (char ch : t) letters = letters || std::isalpha(static_cast<unsigned char>(ch));
    if (!letters) fail(c, fmt::format("field {}: bad number '{}'", i, t));
    fail(c, fmt::format("field {}: bad number or expression '{}' ({})", i, t, e.what()));
  }
  // An overflow (1E999, 1E300*1E300) would travel into the model as inf or NaN.
  if (!std::isfinite(*value)) fail(c, fmt::format("field {}: '{}' is not a finite number", i, t));
  return value;
}

double DeckReader::real(const Command& c, int i, double fallback) const {
  return opt_real(c, i).value_or(fallback);
}

std::optional<int> DeckReader::opt_int(const Command& c, int i) const {
  auto v = opt_real(c, i);
  if (!v) return std::nullopt;
  if (std::fabs(*v) > 2.0e9)
    fail(c, fmt::format("field {}: integer '{}' out of range", i, c.text(i)));
  return static_cast<int>(std::lround(*v));
}

int DeckReader::integer(const Command& c, int i, int fallback) const {
  return opt_int(c, i).value_or(fallback);
}

std::string DeckReader::label(const Command& c, int i) const {
  return to_upper(text_field(c, i));
}

std::string DeckReader::text_field(const Command& c, int i) const {
  const std::string& t = c.text(i);
  if (t.empty()) return t;
  if (t.size() >= 2 && t.front() == '\'' && t.back() == '\'') return t.substr(1, t.size() - 2);
  // A whole field naming a character parameter or a CHAR-array entry gives its text (§A.5).
  if (auto n = split_subscripted_name(t)) {
    const Param* p = params.find(n->name);
    if (p != nullptr &&
        (p->type == ParamType::Text || (p->is_character_array() && n->has_parentheses))) {
      try {
        const Value v = evaluate_value(t, params, &functions_);
        if (is_text(v)) {
          std::string out = std::get<std::string>(v);
          while (!out.empty() && out.back() == ' ') out.pop_back();
          return out;
        }
      } catch (const ExpressionError& e) {
        fail(c, fmt::format("field {}: {}", i, e.what()));
      }
    }
  }
  return t;
}

Value DeckReader::value(const Command& c, int i) const {
  const std::string& t = c.text(i);
  if (t.empty()) return 0.0;
  if (auto v = parse_fortran_number(t)) return *v;
  return eval_value(c, t);
}

Value DeckReader::evaluate_expression(std::string_view expression) const {
  return evaluate_value(expression, params, &functions_);
}

Value DeckReader::eval_value(const Command& c, const std::string& expression) const {
  try {
    return evaluate_value(expression, params, &functions_);
  } catch (const ExpressionError& e) {
    fail(c, fmt::format("bad expression '{}' ({})", expression, e.what()));
  }
}

double DeckReader::eval(const Command& c, const std::string& expression) const {
  if (auto v = parse_fortran_number(trim(expression))) return *v;
  const Value v = eval_value(c, expression);
  if (is_text(v))
    fail(c,
         fmt::format("'{}' is the text '{}', not a number", expression, std::get<std::string>(v)));
  return std::get<double>(v);
}

std::string DeckReader::substitute_percent(const Command& c, const std::string& text) const {
  std::string out;
  std::size_t i = 0;
  while (i < text.size()) {
    if (text[i] != '%') {
      out += text[i++];
      continue;
    }
    if (i + 1 < text.size() && text[i + 1] == '%') {  // %% = a literal %
      out += '%';
      i += 2;
      continue;
    }
    const std::size_t close = text.find('%', i + 1);
    if (close == std::string::npos) {
      out += text.substr(i);
      break;
    }
    const std::string inner = text.substr(i + 1, close - i - 1);
    const Param* p = params.find(trim(inner));
    if (p != nullptr && p->type == ParamType::Table) {
      // %TABLE% stays as written: a load command's value field reads it as a table load
      // (load_field, APDL_MODELING §5.5); any other numeric field rejects it as not a number.
      out += text.substr(i, close - i + 1);
      i = close + 1;
      continue;
    }
    try {
      const Value v = evaluate_value(inner, params, &functions_);
      if (is_text(v)) {
        std::string t = std::get<std::string>(v);
        while (!t.empty() && t.back() == ' ') t.pop_back();
        out += t;
      } else {
        out += format_number(std::get<double>(v));
      }
    } catch (const ExpressionError& e) {
      warn(c, fmt::format("%{}% left as written ({})", inner, e.what()));
      out += text.substr(i, close - i + 1);
    }
    i = close + 1;
  }
  return out;
}

bool DeckReader::on_off(const Command& c, int i, bool fallback) const {
  const std::string l = label(c, i);
  if (l.empty()) return fallback;
  if (l == "ON" || l == "YES" || l == "1" || l == "FULL") return true;
  if (l == "OFF" || l == "NO" || l == "0") return false;
  fail(c, fmt::format("field {}: expected ON or OFF, got '{}'", i, c.text(i)));
}

void DeckReader::require_node(const Command& c, int id) const {
  if (model.nodes.count(id) == 0) fail(c, fmt::format("node {} is not defined", id));
}

std::vector<int> DeckReader::node_range(const Command& c, int node_field, int end_field,
                                        int inc_field) {
  std::vector<int> out;
  // ALL = the selected nodes; a component name = its nodes (APDL_MODELING §1.9).
  const std::string first_label = label(c, node_field);
  if (first_label == "ALL") return require_selected_nodes(*this, c);
  if (auto members = component_members(*this, c, first_label, "NODE")) {
    if (members->empty()) fail(c, fmt::format("component {} has no existing nodes", first_label));
    return *members;
  }
  const auto first = opt_int(c, node_field);
  if (!first) fail(c, fmt::format("field {}: node number missing", node_field));
  const int last = end_field > 0 ? integer(c, end_field, *first) : *first;
  int inc = inc_field > 0 ? integer(c, inc_field, 1) : 1;
  if (inc == 0) inc = 1;
  if (last == *first) {
    require_node(c, *first);
    return {*first};
  }
  if ((static_cast<long long>(last) - *first) * inc < 0)
    fail(c, fmt::format("empty node range {} to {} step {}", *first, last, inc));
  // Walk the defined nodes, not the number range (which may span 10^9 numbers).
  const int lo = std::min(*first, last), hi = std::max(*first, last);
  for (auto it = model.nodes.lower_bound(lo); it != model.nodes.end() && it->first <= hi; ++it)
    if ((static_cast<long long>(it->first) - *first) % inc == 0) out.push_back(it->first);
  if (inc < 0) std::reverse(out.begin(), out.end());
  if (out.empty()) fail(c, fmt::format("no node is defined in the range {} to {}", *first, last));
  return out;
}

void DeckReader::add_element(const Command& c, int id, std::vector<int> nodes) {
  if (id <= 0) fail(c, fmt::format("element number {} must be positive", id));
  const auto type_it = model.element_types.find(modeling.current_type);
  if (type_it == model.element_types.end())
    fail(c, fmt::format("element type {} is not defined (ET missing before TYPE/E)",
                        modeling.current_type));
  const ElementType& type = type_it->second;
  const ElementTypeDescriptor& d = element_type_descriptor(type);
  if (d.defined_by_file)
    fail(c, fmt::format("the active element type is {}: use SE,File (modern) or E,id,unit (4x)",
                        d.name));
  // Trailing blank optional nodes (a beam's orientation node) are not nodes.
  while (static_cast<int>(nodes.size()) > d.n_nodes && nodes.back() == 0) nodes.pop_back();
  if (d.triangle_form_keyopt > 0 && type.key(d.triangle_form_keyopt) == 1) {
    // The 6-node triangle I J K L M N (PLANE183 KEYOPT(1) = 1) in the quadrilateral's form
    // with K = L = O: I J K K, then the midsides L M (K) N of I-J J-K (K-K) K-I.
    // The corners alone leave the midside nodes to EMID (or to the model check, which refuses
    // an element still without them).
    while (!nodes.empty() && nodes.back() == 0) nodes.pop_back();
    if (nodes.size() == 3)
      nodes = {nodes[0], nodes[1], nodes[2], nodes[2], 0, 0, nodes[2], 0};
    else if (nodes.size() == 6)
      nodes = {nodes[0], nodes[1], nodes[2], nodes[2], nodes[3], nodes[4], nodes[2], nodes[5]};
    else
      fail(c, fmt::format("{} with KEYOPT({}) = 1 is the 6-node triangle: E takes the nodes I J "
                          "K L M N (or the corners I J K, EMID adding the midside nodes), got {}",
                          d.name, d.triangle_form_keyopt, nodes.size()));
  }
  const int given = static_cast<int>(nodes.size());
  // A cell with midside nodes takes its corners from E and the rest from EMORE (E has 8 node
  // fields): the positions not given yet are 0 (the cell's corners must all be given).
  const CellTopology& cell = d.topology();
  const int midside_end = cell.midside_nodes > 0 ? cell.n_nodes() : 0;
  if (midside_end > 0 && given >= cell.corner_nodes && given < midside_end)
    nodes.resize(static_cast<std::size_t>(midside_end), 0);
  else if (given < d.least_nodes() || given > d.max_nodes()) {
    std::string range;
    if (d.least_nodes() < d.n_nodes)
      range = fmt::format(" (at least {}: missing corner nodes repeat the last)", d.least_nodes());
    else if (d.n_optional_nodes > 0)
      range = fmt::format(" (and up to {} optional)", d.n_optional_nodes);
    fail(c, fmt::format("{} needs {} node{}, {} given{}", type.ansys_name, d.n_nodes,
                        d.n_nodes == 1 ? "" : "s", given, range));
  }
  // Missing corner nodes repeat the last given one (3-node shell: K repeated as L).
  while (static_cast<int>(nodes.size()) < d.n_nodes) nodes.push_back(nodes.back());
  for (std::size_t k = 0; k < nodes.size(); ++k) {
    const bool midside =
        static_cast<int>(k) >= cell.corner_nodes && static_cast<int>(k) < midside_end;
    if (midside && nodes[k] == 0) continue;  // given by EMORE, or refused (validate_elements)
    if (nodes[k] <= 0)
      fail(c, fmt::format("node {} of element {} is blank or not positive", k + 1, id));
    require_node(c, nodes[k]);
  }
  modeling.emore_element = id;
  modeling.emore_position = given;
  ElementRecord rec;
  rec.id = id;
  rec.type = modeling.current_type;
  rec.real = modeling.current_real;
  rec.mat = modeling.current_mat;
  rec.secnum = modeling.current_secnum;
  rec.esys = modeling.esys;
  rec.nodes = std::move(nodes);
  rec.where = c.where;
  if (model.elements.count(id) == 0) modeling.element_order.push_back(id);
  model.elements[id] = std::move(rec);
}

void DeckReader::validate_elements() {
  if (!modeling.secnum_given)
    for (auto& [id, e] : model.elements)
      if (e.secnum > 0 && model.sections.count(e.secnum) == 0) e.secnum = 0;
  for (const auto& [id, e] : model.elements) {
    const auto t = model.element_types.find(e.type);
    if (t == model.element_types.end())
      throw InputError(e.where,
                       fmt::format("element {}: element type {} is not defined", id, e.type));
    const ElementTypeDescriptor& d = element_type_descriptor(t->second);
    if (d.defined_by_file && e.superelement_file.empty())
      throw InputError(e.where,
                       fmt::format("element {}: {} without a superelement file", id, d.name));
    // A midside node that neither E nor EMORE gave (the element's factory refuses it too):
    // zero, or beyond the nodes given.
    const CellTopology& cell = d.topology();
    for (int k = cell.corner_nodes; cell.midside_nodes > 0 && k < cell.n_nodes(); ++k)
      if (static_cast<std::size_t>(k) >= e.nodes.size() ||
          e.nodes[static_cast<std::size_t>(k)] == 0)
        throw InputError(e.where, fmt::format("element {} ({}): midside node {} (of {}) is not "
                                              "given (E takes the first 8 nodes, EMORE the rest)",
                                              id, t->second.ansys_name, k + 1, cell.n_nodes()));
    const auto section = model.sections.find(e.secnum);
    const bool has_section =
        e.secnum > 0 && section != model.sections.end() && d.accepts_section(section->second.type);
    const bool needs_real = d.real_constants == RealConstantUse::Required ||
                            (d.real_constants == RealConstantUse::UnlessSection && !has_section);
    const bool needs_mat = d.needs_material;
    if (needs_real && model.real_sets.count(e.real) == 0)
      throw InputError(e.where, fmt::format("element {} ({}): real constant set {} is not defined",
                                            id, t->second.ansys_name, e.real));
    if (needs_mat && model.materials.count(e.mat) == 0)
      throw InputError(e.where, fmt::format("element {} ({}): material {} is not defined", id,
                                            t->second.ansys_name, e.mat));
  }
}

void DeckReader::solve_step(std::size_t step) {
  ++solutions;  // results read before this request are out of date
  if (options.host != nullptr) options.host->solve(job, step);
}

std::optional<double> DeckReader::previous_time() const {
  std::optional<double> t;
  auto take = [&](const LoadStep& s) {
    if (s.time_end && (!t || *s.time_end > *t)) t = s.time_end;
  };
  if (dialect == Dialect::Classic4x) {
    for (const auto& s : solution.load_steps_4x) take(s);
  } else {
    if (solution.open_analysis)
      for (const auto& s : job.steps[*solution.open_analysis].analysis->load_steps) take(s);
    for (const auto& [n, s] : solution.lswrite_steps) take(s);
  }
  return t;
}

Job DeckReader::finish() {
  if (processor == kStress && !solution.stress_requests.empty()) {
    Log::warn("/STRESS block not closed by END at the end of the deck; expansion requests kept");
    close_stress_block(*this, solution.stress_where);
  }
  if (options.host != nullptr) options.host->finish(job);
  for (const auto& [name, entry] : skipped)
    job.skipped_unknown.push_back({name, entry.first, entry.second});
  output.to_terminal();
  return std::move(job);
}

}  // namespace deck

namespace {

Job read_impl(const std::shared_ptr<const std::string>& text, const std::string& path,
              const DeckOptions& options) {
  Dialect dialect = Dialect::Modern;
  if (options.dialect) {
    dialect = *options.dialect;
  } else if (std::set<std::string> scanned{deck::canonical_or_self(path)};
             deck::uses_4x(deck::lex_text(*text, path, Dialect::Modern, text), path, scanned)) {
    dialect = Dialect::Classic4x;
  }
  std::string jobname = options.jobname;
  if (jobname.empty()) jobname = std::filesystem::path(path).stem().string();
  Log::info("{}: reading deck ({} dialect)", path, dialect == Dialect::Classic4x ? "4x" : "modern");
  deck::DeckReader reader(options, dialect, jobname);
  reader.run_shared_text(text, path);
  return reader.finish();
}

}  // namespace

Job read_deck(const std::string& path, const DeckOptions& options) {
  return read_impl(
      std::make_shared<const std::string>(deck::read_text_file(path, SourceLocation{})), path,
      options);
}

Job read_deck_text(const std::string& text, const std::string& virtual_path,
                   const DeckOptions& options) {
  return read_impl(std::make_shared<const std::string>(text), virtual_path, options);
}

}  // namespace impactfe
