// Deck reader entry points, the command executor (repeat lines, 4-character names, /INPUT,
// *DO, *IF, *BEGIN/*CREATE blocks) and the field helpers shared by the handlers.
#include "deck/deck_reader.h"

#include <fmt/format.h>

#include <cctype>
#include <cmath>
#include <filesystem>
#include <fstream>
#include <sstream>

#include "deck/deck_context.h"
#include "deck/language_standin.h"
#include "deck/post_support.h"
#include "elements/element_registry.h"

namespace impactfe {

namespace deck {

namespace {

constexpr int kMaxNesting = 20;

std::string read_file(const std::string& path, const SourceLocation& where) {
  std::ifstream in(path, std::ios::binary);
  if (!in) {
    if (where.known()) throw InputError(where, fmt::format("cannot open input file '{}'", path));
    throw InputError(fmt::format("cannot open deck '{}'", path));
  }
  std::ostringstream ss;
  ss << in.rdbuf();
  return ss.str();
}

std::string directory_of(const std::string& path) {
  return std::filesystem::path(path).parent_path().string();
}

std::string join_path(const std::string& dir, const std::string& name) {
  if (dir.empty() || std::filesystem::path(name).is_absolute()) return name;
  return (std::filesystem::path(dir) / name).string();
}

/// /INPUT,Fname,Ext: the file relative to the including deck; without an extension also try
/// Fname.inp and Fname.mac.
std::string resolve_input(const std::string& includer, const std::string& fname,
                          const std::string& ext) {
  const std::string dir = directory_of(includer);
  std::string name = ext.empty() ? fname : fname + "." + ext;
  std::string path = join_path(dir, name);
  if (!ext.empty() || std::filesystem::exists(path)) return path;
  for (const char* e : {".inp", ".mac"}) {
    const std::string alt = join_path(dir, fname + e);
    if (std::filesystem::exists(alt)) return alt;
  }
  return path;
}

/// Spec §2.3: 4x when the deck uses KAN, KAY, ITER, LWRITE, AFWRITE, /INPUT,27, /STRESS or
/// *BEGIN (a 4x *DO names a *BEGIN block, so *BEGIN already decides). Included files count.
bool uses_4x(const std::vector<RawCommand>& cmds, const std::string& path, int depth) {
  for (const auto& c : cmds) {
    const std::string& n = c.name;
    if (n == "KAN" || n == "KAY" || n == "ITER" || n == "LWRITE" || n == "AFWRITE" ||
        n == "/STRESS" || n == "*BEGIN")
      return true;
    if (n == "/INPUT" && !c.fields.empty()) {
      if (trim(c.fields[0]) == "27") return true;
      if (depth < kMaxNesting) {
        const std::string inc =
            resolve_input(path, c.fields[0], c.fields.size() > 1 ? c.fields[1] : std::string());
        std::ifstream in(inc, std::ios::binary);
        if (in) {
          std::ostringstream ss;
          ss << in.rdbuf();
          if (uses_4x(lex_text(ss.str(), inc, Dialect::Modern), inc, depth + 1)) return true;
        }
      }
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
    : options(opts), model(job.model), dialect(d) {
  model.dialect = d;
  model.jobname = jobname;
  jobname_from_option = !opts.jobname.empty();
  // 4x decks integrate with Houbolt (the only 4.2 integrator); modern decks default to Newmark.
  model.options.integrator =
      d == Dialect::Classic4x ? IntegratorKind::Houbolt : IntegratorKind::Newmark;
  // MAPDL elements carry SECNUM 1 unless changed; 4x had no sections.
  current_secnum = d == Dialect::Modern ? 1 : 0;
}

void DeckReader::fail(const Command& c, const std::string& message) const {
  throw InputError(c.where, message);
}

void DeckReader::warn(const Command& c, const std::string& message) const {
  Log::warn("{}:{}: {}: {}", c.where.file, c.where.line, c.where.command, message);
}

void DeckReader::ignore(const Command& c) {
  job.ignored_commands.push_back(fmt::format("{}:{}: {}", c.where.file, c.where.line, c.name));
  Log::info("{}:{}: {}: graphics/print-only command ignored", c.where.file, c.where.line, c.name);
}

std::optional<double> DeckReader::opt_real(const Command& c, int i) const {
  const std::string& t = c.text(i);
  if (t.empty()) return std::nullopt;
  if (auto v = parse_fortran_number(t)) return v;
  try {
    return evaluate(t, params);
  } catch (const ExpressionError& e) {
    bool letters = false;
    for (char ch : t) letters = letters || std::isalpha(static_cast<unsigned char>(ch));
    if (!letters) fail(c, fmt::format("field {}: bad number '{}'", i, t));
    fail(c, fmt::format("field {}: bad number or expression '{}' ({})", i, t, e.what()));
  }
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
  return to_upper(c.text(i));
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
  if ((last - *first) * inc < 0)
    fail(c, fmt::format("empty node range {} to {} step {}", *first, last, inc));
  for (int n = *first; inc > 0 ? n <= last : n >= last; n += inc)
    if (model.nodes.count(n) != 0) out.push_back(n);
  if (out.empty()) fail(c, fmt::format("no node is defined in the range {} to {}", *first, last));
  return out;
}

void DeckReader::add_element(const Command& c, int id, std::vector<int> nodes) {
  if (id <= 0) fail(c, fmt::format("element number {} must be positive", id));
  const auto type_it = model.element_types.find(current_type);
  if (type_it == model.element_types.end())
    fail(c, fmt::format("element type {} is not defined (ET missing before TYPE/E)", current_type));
  const ElementType& type = type_it->second;
  const ElementTypeDescriptor& d = element_type_descriptor(type);
  if (d.defined_by_file)
    fail(c, fmt::format("the active element type is {}: use SE,File (modern) or E,id,unit (4x)",
                        d.name));
  // Trailing blank optional nodes (a beam's orientation node) are not nodes.
  while (static_cast<int>(nodes.size()) > d.n_nodes && nodes.back() == 0) nodes.pop_back();
  const int given = static_cast<int>(nodes.size());
  if (given < d.least_nodes() || given > d.max_nodes()) {
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
    if (nodes[k] <= 0)
      fail(c, fmt::format("node {} of element {} is blank or not positive", k + 1, id));
    require_node(c, nodes[k]);
  }
  ElementRecord rec;
  rec.id = id;
  rec.type = current_type;
  rec.real = current_real;
  rec.mat = current_mat;
  rec.secnum = current_secnum;
  rec.nodes = std::move(nodes);
  rec.where = c.where;
  if (model.elements.count(id) == 0) element_order.push_back(id);
  model.elements[id] = std::move(rec);
}

void DeckReader::validate_elements() {
  if (!secnum_given)
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
    for (const auto& s : load_steps_4x) take(s);
  } else {
    if (open_analysis)
      for (const auto& s : job.steps[*open_analysis].analysis->load_steps) take(s);
    for (const auto& [n, s] : lswrite_steps) take(s);
  }
  return t;
}

// ---- executor ---------------------------------------------------------------------------------

Command DeckReader::resolve(const RawCommand& raw) {
  Command c;
  c.fields = raw.fields;
  c.rest = raw.rest;
  c.assignment = raw.assignment;
  c.where.file = raw.file;
  c.where.line = raw.line;
  if (raw.repeat) {
    if (last_name_.empty()) {
      c.where.command = ",";
      throw InputError(c.where, "repeat line (leading comma) with no previous command to repeat");
    }
    c.name = last_name_;
  } else {
    c.name = raw.name;
  }
  c.where.command = c.name;
  return c;
}

void DeckReader::run_file(const std::string& path, int depth, const SourceLocation& where) {
  if (depth > kMaxNesting)
    throw InputError(where, fmt::format("/INPUT nesting deeper than {} files", kMaxNesting));
  const std::string text = read_file(path, where);
  const auto cmds = lex_text(text, path, dialect);
  const bool saved_eof = eof_;
  eof_ = false;
  run(cmds, 0, cmds.size(), depth);
  eof_ = saved_eof;
}

void DeckReader::run_text(const std::string& text, const std::string& path) {
  const auto cmds = lex_text(text, path, dialect);
  run(cmds, 0, cmds.size(), 0);
}

std::size_t DeckReader::find_block_end(const std::vector<RawCommand>& cmds, std::size_t begin,
                                       std::size_t end, const char* open, const char* close,
                                       const Command& opener) const {
  int depth = 0;
  for (std::size_t j = begin; j < end; ++j) {
    const std::string& n = cmds[j].name;
    if (n == open) ++depth;
    if (n == close) {
      if (depth == 0) return j;
      --depth;
    }
  }
  fail(opener, fmt::format("no matching {} for this {}", close, opener.name));
}

void DeckReader::run_do(const std::vector<RawCommand>& cmds, std::size_t& i, std::size_t end,
                        int depth, const Command& c) {
  const std::string first = label(c, 1);
  if (macros.count(first) != 0 && dialect == Dialect::Classic4x) {
    // 4x *DO,Block,N1,N2: replay the *BEGIN block once per k = N1..N2; after each pass every
    // parameter with a *SET increment is incremented (§3.29).
    const int n1 = integer(c, 2, 1);
    const int n2 = integer(c, 3, n1);
    for (int k = n1; k <= n2; ++k) {
      run_macro(c, first, depth);
      for (const auto& [name, inc] : increments)
        params.set(name, params.get(name).value_or(0.0) + inc);
    }
    ++i;
    return;
  }
  if (!is_parameter_name(first))
    fail(c, fmt::format("'{}' is neither a *BEGIN block nor a loop parameter", c.text(1)));
  if (depth >= kMaxNesting) fail(c, "*DO nesting deeper than 20");
  const std::size_t close = find_block_end(cmds, i + 1, end, "*DO", "*ENDDO", c);
  const double ival = real(c, 2, 0.0);
  const auto fval = opt_real(c, 3);
  if (!fval) fail(c, "*DO: final value FVAL missing");
  const double inc = real(c, 4, 1.0);
  if (inc == 0.0) fail(c, "*DO: increment is zero");
  const double eps = 1e-10 * std::max(1.0, std::fabs(*fval));
  for (double v = ival; inc > 0 ? v <= *fval + eps : v >= *fval - eps; v += inc) {
    params.set(first, v);
    run(cmds, i + 1, close, depth + 1);
    if (eof_) return;
  }
  i = close + 1;
}

namespace {
bool compare(const std::string& op, double a, double b) {
  constexpr double tol = 1e-10;  // APDL_SCRIPTING S7: absolute tolerance
  if (op == "EQ") return std::fabs(a - b) <= tol;
  if (op == "NE") return std::fabs(a - b) > tol;
  if (op == "LT") return a < b - tol;
  if (op == "GT") return a > b + tol;
  if (op == "LE") return a <= b + tol;
  if (op == "GE") return a >= b - tol;
  if (op == "ABLT") return std::fabs(a) < std::fabs(b) - tol;
  if (op == "ABGT") return std::fabs(a) > std::fabs(b) + tol;
  throw ExpressionError("unknown *IF operator " + op);
}
}  // namespace

void DeckReader::run_if(const std::vector<RawCommand>& cmds, std::size_t& i, std::size_t end,
                        int depth, const Command& c) {
  // Branch starts: the *IF itself, each *ELSEIF, *ELSE; then *ENDIF (nested *IF..THEN skipped).
  std::vector<std::size_t> marks{i};
  std::size_t close = end;
  int nest = 0;
  for (std::size_t j = i + 1; j < end; ++j) {
    const std::string& n = cmds[j].name;
    if (n == "*IF" && cmds[j].fields.size() >= 4 && to_upper(trim(cmds[j].fields[3])) == "THEN")
      ++nest;
    else if (n == "*ENDIF") {
      if (nest == 0) {
        close = j;
        break;
      }
      --nest;
    } else if (nest == 0 && (n == "*ELSEIF" || n == "*ELSE")) {
      marks.push_back(j);
    }
  }
  if (close == end) fail(c, "no matching *ENDIF for this *IF");
  marks.push_back(close);
  for (std::size_t b = 0; b + 1 < marks.size(); ++b) {
    const RawCommand& head = cmds[marks[b]];
    bool take = head.name == "*ELSE";
    if (!take) {
      Command h = resolve(head);
      if (label(h, 4) != "THEN")
        fail(h, "only the block form *IF,VAL1,Oper,VAL2,THEN is supported");
      try {
        take = compare(label(h, 2), real(h, 1, 0.0), real(h, 3, 0.0));
      } catch (const ExpressionError& e) {
        fail(h, e.what());
      }
    }
    if (take) {
      run(cmds, marks[b] + 1, marks[b + 1], depth + 1);
      break;
    }
  }
  i = close + 1;
}

void DeckReader::run_macro(const Command& c, const std::string& name, int depth) {
  if (depth >= kMaxNesting) fail(c, "macro nesting deeper than 20");
  const auto cmds = macros.at(name);  // copy: the macro may redefine itself
  run(cmds, 0, cmds.size(), depth + 1);
  eof_ = false;
}

void DeckReader::run(const std::vector<RawCommand>& cmds, std::size_t begin, std::size_t end,
                     int depth) {
  std::size_t i = begin;
  while (i < end && !eof_) {
    Command c = resolve(cmds[i]);
    const CommandSpec* spec = find_command(c.name);
    if (spec == nullptr && dialect == Dialect::Classic4x) {
      bool ambiguous = false;
      spec = find_command_by_prefix(c.name, ambiguous);
      if (ambiguous) fail(c, "ambiguous command name (4x: only the first four characters count)");
      if (spec != nullptr) {
        warn(c, fmt::format("taken as {} (4x: only the first four characters are significant)",
                            spec->name));
        c.name = spec->name;
        c.where.command = c.name;
      }
    }
    if (spec == nullptr) {
      if (options.skip_unknown) {
        warn(c, "unknown command skipped (--skip-unknown)");
        job.ignored_commands.push_back(
            fmt::format("{}:{}: {} (unknown)", c.where.file, c.where.line, c.name));
        last_name_ = c.name;
        ++i;
        continue;
      }
      fail(c, "unknown command");
    }
    last_name_ = c.name;
    // ---- control commands ----
    if (c.name == "*DO") {
      run_do(cmds, i, end, depth, c);
      continue;
    }
    if (c.name == "*IF") {
      run_if(cmds, i, end, depth, c);
      continue;
    }
    if (c.name == "*ENDDO" || c.name == "*ENDIF" || c.name == "*ELSE" || c.name == "*ELSEIF")
      fail(c, fmt::format("{} without a matching opening command", c.name));
    if (c.name == "*BEGIN" || c.name == "*CREATE") {
      const std::string name = label(c, 1);
      if (name.empty()) fail(c, "block name missing");
      const std::size_t close = find_block_end(cmds, i + 1, end, c.name.c_str(), "*END", c);
      macros[name] = std::vector<RawCommand>(cmds.begin() + static_cast<long>(i) + 1,
                                             cmds.begin() + static_cast<long>(close));
      Log::info("{}:{}: {}: block {} recorded ({} commands)", c.where.file, c.where.line, c.name,
                name, close - i - 1);
      i = close + 1;
      continue;
    }
    if (c.name == "*END") fail(c, "*END without *BEGIN or *CREATE");
    if (c.name == "*USE") {
      const std::string name = label(c, 1);
      if (macros.count(name) == 0)
        fail(c, fmt::format("macro '{}' is not defined (*CREATE)", name));
      for (int a = 2; a <= std::min(c.n_fields(), 19); ++a)
        if (!c.blank(a)) params.set(fmt::format("ARG{}", a - 1), real(c, a, 0.0));
      run_macro(c, name, depth);
      ++i;
      continue;
    }
    if (c.name == "*VWRITE") {  // language stand-in: the next line is the format
      if (i + 1 >= end) fail(c, "format line missing after *VWRITE");
      const RawCommand& f = cmds[i + 1];
      standin_vwrite(*this, c, f.name + (f.rest.empty() ? "" : "," + f.rest));
      i += 2;
      continue;
    }
    if (c.name == "/EOF") {
      eof_ = true;
      return;
    }
    if (c.name == "/INPUT") {
      if (c.blank(1)) fail(c, "file name missing");
      if (dialect == Dialect::Classic4x && trim(c.text(1)) == "27") {
        run_frozen_analysis(*this, c);
      } else {
        const std::string path = resolve_input(c.where.file, c.text(1), c.text(2));
        run_file(path, depth + 1, c.where);
      }
      ++i;
      continue;
    }
    dispatch(c, *spec);
    ++i;
  }
}

void DeckReader::dispatch(const Command& c, const CommandSpec& spec) {
  if ((spec.processors & processor) == 0) {
    fail(c, fmt::format("command not valid in {}", processor_name(processor)));
  }
  spec.handler(*this, c);
}

Job DeckReader::finish() {
  if (processor == kStress && !stress_requests.empty()) {
    Log::warn("/STRESS block not closed by END at the end of the deck; expansion requests kept");
    close_stress_block(*this, stress_where);
  }
  if (options.host != nullptr) options.host->finish(job);
  return std::move(job);
}

}  // namespace deck

namespace {

Job read_impl(const std::string& text, const std::string& path, const DeckOptions& options) {
  Dialect dialect = Dialect::Modern;
  if (options.dialect) {
    dialect = *options.dialect;
  } else if (deck::uses_4x(deck::lex_text(text, path, Dialect::Modern), path, 0)) {
    dialect = Dialect::Classic4x;
  }
  std::string jobname = options.jobname;
  if (jobname.empty()) jobname = std::filesystem::path(path).stem().string();
  Log::info("{}: reading deck ({} dialect)", path, dialect == Dialect::Classic4x ? "4x" : "modern");
  deck::DeckReader reader(options, dialect, jobname);
  reader.run_text(text, path);
  return reader.finish();
}

}  // namespace

Job read_deck(const std::string& path, const DeckOptions& options) {
  return read_impl(deck::read_file(path, SourceLocation{}), path, options);
}

Job read_deck_text(const std::string& text, const std::string& virtual_path,
                   const DeckOptions& options) {
  return read_impl(text, virtual_path, options);
}

}  // namespace impactfe
