// The command executor (APDL_SCRIPTING §A.10–§A.13): files, macros, *DO / *DOWHILE loops,
// *IF blocks and one-line *IF actions, *GO / :labels, *EXIT / *CYCLE, *REPEAT, /EOF, and the
// 4x *BEGIN blocks replayed by *DO. Block structure is matched once per file (or macro) in a
// linear pass; a structural error (an *IF without *ENDIF, nesting too deep) is raised when
// execution reaches the offending line, as MAPDL reports it. Recursion is bounded everywhere, so
// no deck can overflow the stack or loop forever.
#include <fmt/format.h>

#include <algorithm>
#include <cmath>
#include <set>

#include "core/files.h"
#include "deck/deck_context.h"

namespace impactfe::deck {

namespace {

constexpr int kMaxFrames = 20;      // /INPUT files and macros, shared (§A.13)
constexpr int kMaxDoNesting = 20;   // §A.10
constexpr int kMaxIfNesting = 100;  // §A.11 asks for at least 20
constexpr int kMaxRecursion = 400;  // executor depth over all frames
constexpr std::size_t kNone = static_cast<std::size_t>(-1);

std::string field_upper(const RawCommand& c, std::size_t i) {
  return i < c.fields.size() ? to_upper(trim(c.fields[i])) : std::string();
}

/// *IF,...,THEN (Base1 = THEN, or Base2 = THEN after AND/OR/XOR) opens a block.
bool is_block_if(const RawCommand& c) {
  const std::string base1 = field_upper(c, 3);
  if (base1 == "AND" || base1 == "OR" || base1 == "XOR") return field_upper(c, 7) == "THEN";
  return base1 == "THEN";
}

std::string label_key(std::string_view text) {
  std::string l = to_upper(trim(text));
  if (!l.empty() && l[0] == ':') l.erase(0, 1);
  return l.substr(0, 8);  // MAPDL labels: 8 significant characters
}

SourceLocation location_of(const RawCommand& c) {
  SourceLocation w;
  if (c.file) w.file = *c.file;
  w.line = c.line;
  w.command = c.name.empty() ? std::string(",") : c.name;
  return w;
}

bool compare_numbers(const std::string& op, double a, double b) {
  constexpr double tol = 1e-10;  // APDL_SCRIPTING S7: absolute tolerance
  if (op == "EQ") return std::fabs(a - b) <= tol;
  if (op == "NE") return std::fabs(a - b) > tol;
  if (op == "LT") return a < b - tol;
  if (op == "GT") return a > b + tol;
  if (op == "LE") return a <= b + tol;
  if (op == "GE") return a >= b - tol;
  if (op == "ABLT") return std::fabs(a) < std::fabs(b) - tol;
  if (op == "ABGT") return std::fabs(a) > std::fabs(b) + tol;
  throw ExpressionError(fmt::format("unknown operator '{}' (EQ NE LT GT LE GE ABLT ABGT)", op));
}

std::string rtrim(std::string s) {
  while (!s.empty() && s.back() == ' ') s.pop_back();
  return s;
}

/// Counts the executor depth; refuses more than kMaxRecursion levels.
struct DepthGuard {
  DepthGuard(int& depth, const DeckReader& r, const Command& c) : depth_(depth) {
    if (++depth_ > kMaxRecursion) {
      --depth_;
      r.fail(c,
             fmt::format("blocks, files and macros nested deeper than {} levels", kMaxRecursion));
    }
  }
  ~DepthGuard() { --depth_; }
  int& depth_;
};

}  // namespace

// ---- block structure
// -----------------------------------------------------------------------------

namespace {

/// A command name as the executor resolves it (exact, then the dialect's abbreviation rule),
/// or the name itself when it is not a known command or is ambiguous.
std::string block_name(const std::string& name, Dialect dialect) {
  if (name.empty() || name[0] != '*' || find_command(name) != nullptr) return name;
  bool ambiguous = false;
  const CommandSpec* spec = dialect == Dialect::Classic4x
                                ? find_command_by_prefix(name, ambiguous)
                                : find_command_by_abbreviation(name, ambiguous);
  if (spec == nullptr && !ambiguous && dialect == Dialect::Modern)
    spec = find_command_by_longer_spelling(name);
  return spec != nullptr && !ambiguous ? spec->name : name;
}

}  // namespace

struct DeckReader::Program {
  std::vector<RawCommand>& cmds;
  std::vector<std::size_t> match;                            // opener → *ENDDO / *ENDIF / *END
  std::map<std::size_t, std::vector<std::size_t>> branches;  // *IF block → *ELSEIF / *ELSE
  std::map<std::size_t, std::string> error;  // raised when the line is reached (few lines)
  std::vector<int> depth;                    // block depth of each line
  std::vector<std::pair<std::string, std::size_t>> labels;

  Program(std::vector<RawCommand>& c, Dialect dialect)
      : cmds(c), match(c.size(), kNone), depth(c.size(), 0) {
    struct Open {
      std::size_t at;
      bool is_do;
    };
    std::vector<Open> stack;
    std::set<std::string> begin_names;  // 4x: *DO,Name replays a *BEGIN block (no *ENDDO)
    int n_do = 0, n_if = 0;
    auto close = [&](std::size_t i, bool is_do) {
      const char* want = is_do ? "*ENDDO" : "*ENDIF";
      while (!stack.empty() && stack.back().is_do != is_do) {
        const Open o = stack.back();
        error[o.at] =
            fmt::format("no matching {} for this {} ({} at line {} closes an outer block)",
                        o.is_do ? "*ENDDO" : "*ENDIF", o.is_do ? "*DO" : "*IF", want, cmds[i].line);
        (o.is_do ? n_do : n_if)--;
        stack.pop_back();
      }
      if (stack.empty()) {
        error[i] = fmt::format("{} without a matching opening command ({})", want,
                               is_do ? "*DO or *DOWHILE" : "*IF,...,THEN");
        return;
      }
      match[stack.back().at] = i;
      (is_do ? n_do : n_if)--;
      stack.pop_back();
    };
    for (std::size_t i = 0; i < cmds.size(); ++i) {
      const RawCommand& r = cmds[i];
      depth[i] = static_cast<int>(stack.size());
      if (r.format_line || r.repeat) continue;
      // The name the command runs as: abbreviations resolve like DeckReader::lookup does, so
      // that e.g. a 4x *BEGINELEMENTS opens the block it runs as (*BEGIN).
      const std::string n = block_name(r.name, dialect);
      if (n == "*CREATE" || n == "*BEGIN") {
        if (n == "*BEGIN") begin_names.insert(field_upper(r, 0));
        std::size_t j = i + 1;
        while (j < cmds.size() && !(cmds[j].name == "*END" && !cmds[j].format_line)) ++j;
        if (j == cmds.size()) {
          error[i] = fmt::format("no *END for this {}", n);
          break;  // the rest of the file is its body
        }
        match[i] = j;
        for (std::size_t k = i + 1; k <= j; ++k) depth[k] = depth[i];
        i = j;
      } else if (n == "*DO" || n == "*DOWHILE") {
        if (n == "*DO" && dialect == Dialect::Classic4x && begin_names.count(field_upper(r, 0)))
          continue;
        stack.push_back({i, true});
        if (++n_do > kMaxDoNesting)
          error[i] = fmt::format("*DO loops nested deeper than {} levels", kMaxDoNesting);
      } else if (n == "*IF" && is_block_if(r)) {
        stack.push_back({i, false});
        if (++n_if > kMaxIfNesting)
          error[i] = fmt::format("*IF blocks nested deeper than {} levels", kMaxIfNesting);
      } else if (n == "*ELSEIF" || n == "*ELSE") {
        if (stack.empty() || stack.back().is_do) {
          error[i] = fmt::format("{} without a matching opening command (*IF,...,THEN)", n);
          continue;
        }
        auto& b = branches[stack.back().at];
        if (!b.empty() && cmds[b.back()].name == "*ELSE")  // reported at the *IF, always reached
          error[stack.back().at] =
              fmt::format("{} at line {} after the *ELSE of this *IF block", n, cmds[i].line);
        b.push_back(i);
      } else if (n == "*ENDDO") {
        close(i, true);
      } else if (n == "*ENDIF") {
        close(i, false);
      } else if (n == "*END") {
        error[i] = "*END without *CREATE or *BEGIN";
      } else if (!n.empty() && n[0] == ':') {
        labels.emplace_back(label_key(n), i);
      }
    }
    for (const Open& o : stack)
      if (error[o.at].empty())
        error[o.at] = o.is_do ? fmt::format("no matching *ENDDO for this {}", cmds[o.at].name)
                              : "no matching *ENDIF for this *IF";
  }

  /// Frees the text of the top-level commands before `i` (a top-level command about to run).
  /// Without labels nothing jumps back to them: *DO and *IF bodies are nested (never
  /// released), and a *CREATE body was copied when its block ran. A deck of 10⁵ node and
  /// element lines otherwise keeps its tokens through the whole solution (issue 11: 8 MB on the
  /// shell dome 160, ~0.2 kB a line).
  void release_before(std::size_t i) {
    if (!labels.empty()) return;
    for (; released < i; ++released) {
      if (depth[released] != 0) continue;
      RawCommand& r = cmds[released];
      const int line = r.line;
      auto file = std::move(r.file);
      r = RawCommand{};
      r.line = line;
      r.file = std::move(file);
      r.released = true;
    }
  }
  std::size_t released = 0;  // commands before this index are released where at top level
};

struct DeckReader::Frame {
  Program& program;
  int loop_depth = 0;
  std::string jump_label;
  std::size_t jump_from = 0;
  SourceLocation jump_where;
};

// ---- running a program -----------------------------------------------------------------------

void DeckReader::run_program(std::vector<RawCommand>& cmds, const std::string& frame_name,
                             const SourceLocation& where) {
  if (static_cast<int>(active_.size()) > kMaxFrames)
    throw InputError(
        where, fmt::format("/INPUT files and macros nested deeper than {} levels", kMaxFrames));
  for (const auto& a : active_)
    if (a == frame_name) {
      std::string chain;
      for (auto it = std::find(active_.begin(), active_.end(), a); it != active_.end(); ++it)
        chain += *it + " -> ";
      throw InputError(where, fmt::format("recursive call refused: {} is already running ({}{})",
                                          frame_name, chain, frame_name));
    }
  Program program(cmds, dialect);
  Frame frame{program};
  active_.push_back(frame_name);
  try {
    std::size_t start = 0;
    for (;;) {
      const Flow flow = run_range(frame, start, cmds.size());
      if (flow != Flow::Jump) break;
      // *GO / *IF,...,:label: the label searched forward first, then from the file start.
      const std::string want = label_key(frame.jump_label);
      std::size_t target = kNone;
      for (const auto& [name, at] : program.labels)
        if (name == want && at > frame.jump_from && target == kNone) target = at;
      for (const auto& [name, at] : program.labels)
        if (name == want && target == kNone) target = at;
      if (target == kNone)
        throw InputError(frame.jump_where, fmt::format("label :{} not found in this file", want));
      if (program.depth[target] > 0)
        throw InputError(frame.jump_where,
                         fmt::format("label :{} (line {}) lies inside a *DO or *IF block; a jump "
                                     "may only reach a label outside blocks",
                                     want, cmds[target].line));
      start = target + 1;
    }
  } catch (...) {
    active_.pop_back();
    throw;
  }
  active_.pop_back();
}

// ---- one command ------------------------------------------------------------------------------

Command DeckReader::resolve(const RawCommand& raw) {
  Command c;
  c.fields = raw.fields;
  c.rest = raw.rest;
  c.assignment = raw.assignment;
  c.block = raw.block;
  c.block_line = raw.block_line;
  if (raw.file) c.where.file = *raw.file;
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
  // %expr% substitution (§A.5 rule 3); not in the Par field of *SET / *DO / *GET / *DIM.
  if (c.name.find('%') != std::string::npos) {
    c.name = to_upper(substitute_percent(c, c.name));
    c.where.command = c.name;
  }
  const bool par_field = c.assignment || c.name == "*SET" || c.name == "*DO" || c.name == "*GET" ||
                         c.name == "*DIM" || c.name == "*DOWHILE";
  for (std::size_t k = par_field ? 1 : 0; k < c.fields.size(); ++k)
    if (c.fields[k].find('%') != std::string::npos)
      c.fields[k] = substitute_percent(c, c.fields[k]);
  if (c.rest.find('%') != std::string::npos) c.rest = substitute_percent(c, c.rest);
  return c;
}

const CommandSpec* DeckReader::lookup(Command& c) {
  const CommandSpec* spec = find_command(c.name);
  if (spec != nullptr) return spec;
  bool ambiguous = false;
  if (dialect == Dialect::Classic4x) {
    spec = find_command_by_prefix(c.name, ambiguous);
    if (ambiguous) fail(c, "ambiguous command name (4x: only the first four characters count)");
    if (spec != nullptr)
      warn(c, fmt::format("taken as {} (4x: only the first four characters are significant)",
                          spec->name));
  } else {
    spec = find_command_by_abbreviation(c.name, ambiguous);
    if (ambiguous) fail(c, "ambiguous abbreviation (several commands begin with it)");
    if (spec != nullptr)
      Log::info("{}:{}: {}: taken as {}", c.where.file, c.where.line, c.name, spec->name);
  }
  if (spec != nullptr) {
    c.name = spec->name;
    c.where.command = c.name;
  }
  return spec;
}

void DeckReader::dispatch(const Command& c, const CommandSpec& spec) {
  if ((spec.processors & processor) == 0)
    fail(c, fmt::format("command not valid in {}", processor_name(processor)));
  if (spec.refused != nullptr) fail(c, spec.refused);
  spec.handler(*this, c);
}

void DeckReader::count_work(const Command& c, long long units) {
  // Loop trips and repetitions count as well as commands: two nested empty *DO loops of 10⁷
  // trips each execute only two commands per outer trip but 10¹⁴ trips in all.
  executed_ += units;
  if (executed_ > options.max_commands)
    fail(c, fmt::format("more than {} commands and loop trips executed (a SAVE or RESUME "
                        "counts as {} plus one per {} bytes of the database): a loop that does "
                        "not end?",
                        options.max_commands, kDatabaseWork, kDatabaseBytesPerWork));
}

void DeckReader::repeat_previous(const Command& c) {
  // *REPEAT,NTOT,VINC1,...,VINC11: the previous command NTOT-1 more times, field k advanced by
  // VINCk each time.
  if (!last_command_) fail(c, "no previous command to repeat");
  const int ntot = integer(c, 1, 1);
  if (ntot < 1 || ntot > kMaxLoopTrips)
    fail(c, fmt::format("NTOT = {} out of range (1 to {})", ntot, kMaxLoopTrips));
  const Command base = *last_command_;
  std::vector<double> inc(11, 0.0);
  for (int k = 1; k <= 11; ++k) inc[static_cast<std::size_t>(k - 1)] = real(c, k + 1, 0.0);
  const CommandSpec* spec = find_command(base.name);
  IMPACTFE_CHECK(spec != nullptr && spec->handler != nullptr, "*REPEAT of a control command");
  for (int n = 1; n < ntot; ++n) {
    count_executed(c);
    Command rep = base;
    rep.where = c.where;
    rep.where.command = base.name;
    for (int k = 1; k <= 11; ++k) {
      const double d = inc[static_cast<std::size_t>(k - 1)];
      if (d == 0.0) continue;
      if (rep.fields.size() < static_cast<std::size_t>(k)) rep.fields.resize(k);
      const double v = base.blank(k) ? 0.0 : real(base, k, 0.0);
      rep.fields[static_cast<std::size_t>(k - 1)] = format_number(v + n * d);
    }
    dispatch(rep, *spec);
  }
}

// ---- loops and conditions ----------------------------------------------------------------------

DeckReader::Flow DeckReader::run_do(Frame& f, std::size_t i, const Command& c) {
  const std::string par = label(c, 1);
  if (!is_parameter_name(par))
    fail(c, fmt::format("'{}' is neither a *BEGIN block nor a loop parameter", c.text(1)));
  const double ival = real(c, 2, 0.0);
  const auto fval = opt_real(c, 3);
  if (!fval) fail(c, "final value FVAL missing");
  const double inc = real(c, 4, 1.0);
  if (inc == 0.0) fail(c, "increment INC is zero");
  // Trip count fixed at *DO (§A.10): a body that changes Par does not change it.
  const double span = (*fval - ival) / inc;
  const double trips = std::floor(span + 1e-10 * std::max(1.0, std::fabs(span))) + 1.0;
  if (trips > static_cast<double>(kMaxLoopTrips))
    fail(c, fmt::format("{:.6g} trips refused (at most {} per loop)", trips, kMaxLoopTrips));
  const long long n = trips < 0.0 ? 0 : static_cast<long long>(trips);
  const std::size_t close = f.program.match[i];
  DepthGuard guard(nesting_, *this, c);
  ++f.loop_depth;
  Flow result = Flow::Normal;
  for (long long t = 0; t < n; ++t) {
    count_executed(c);
    params.set(par, ival + static_cast<double>(t) * inc);
    const Flow flow = run_range(f, i + 1, close);
    if (flow == Flow::Exit) break;
    if (flow == Flow::Normal || flow == Flow::Cycle) continue;
    if (flow == Flow::Jump)
      throw InputError(f.jump_where,
                       "a jump (*GO, *IF,...,:label) may not leave a *DO loop; "
                       "use *EXIT");
    result = flow;
    break;
  }
  --f.loop_depth;
  return result;
}

DeckReader::Flow DeckReader::run_dowhile(Frame& f, std::size_t i, const Command& c) {
  // *DOWHILE,Par: repeat while Par > 0 (Par read before each trip).
  const std::string par = c.text(1);
  if (par.empty()) fail(c, "loop parameter missing");
  const std::size_t close = f.program.match[i];
  DepthGuard guard(nesting_, *this, c);
  ++f.loop_depth;
  Flow result = Flow::Normal;
  for (long long t = 0;; ++t) {
    if (eval(c, par) <= 0.0) break;
    if (t >= kMaxLoopTrips)
      fail(c, fmt::format("more than {} trips: the loop does not end", kMaxLoopTrips));
    count_executed(c);
    const Flow flow = run_range(f, i + 1, close);
    if (flow == Flow::Exit) break;
    if (flow == Flow::Normal || flow == Flow::Cycle) continue;
    if (flow == Flow::Jump)
      throw InputError(f.jump_where,
                       "a jump (*GO, *IF,...,:label) may not leave a *DO loop; "
                       "use *EXIT");
    result = flow;
    break;
  }
  --f.loop_depth;
  return result;
}

bool DeckReader::if_condition(const Command& c, int first, bool& has_second) {
  auto clause = [&](int k) {
    const std::string op = label(c, k + 1);
    if (op.empty()) fail(c, fmt::format("field {}: operator missing", k + 1));
    const Value a = value(c, k);
    const Value b = value(c, k + 2);
    if (is_text(a) || is_text(b)) {
      if (!is_text(a) || !is_text(b)) fail(c, "a text is compared with a number");
      if (op != "EQ" && op != "NE")
        fail(c, fmt::format("texts compare only with EQ or NE, not {}", op));
      const bool same = rtrim(std::get<std::string>(a)) == rtrim(std::get<std::string>(b));
      return op == "EQ" ? same : !same;
    }
    try {
      return compare_numbers(op, std::get<double>(a), std::get<double>(b));
    } catch (const ExpressionError& e) {
      fail(c, e.what());
    }
  };
  const bool first_clause = clause(first);
  const std::string conj = label(c, first + 3);
  has_second = conj == "AND" || conj == "OR" || conj == "XOR";
  if (!has_second) return first_clause;
  const bool second = clause(first + 4);
  if (conj == "AND") return first_clause && second;
  if (conj == "OR") return first_clause || second;
  return first_clause != second;
}

DeckReader::Flow DeckReader::run_if(Frame& f, std::size_t i, const Command& c) {
  bool has_second = false;
  const bool cond = if_condition(c, 1, has_second);
  const std::string action = label(c, has_second ? 8 : 4);
  if (action == "THEN") {
    DepthGuard guard(nesting_, *this, c);
    std::vector<std::size_t> heads{i};
    if (auto it = f.program.branches.find(i); it != f.program.branches.end())
      heads.insert(heads.end(), it->second.begin(), it->second.end());
    heads.push_back(f.program.match[i]);
    for (std::size_t b = 0; b + 1 < heads.size(); ++b) {
      bool take = cond;
      if (b > 0) {
        const RawCommand& head = f.program.cmds[heads[b]];
        if (head.name == "*ELSE") {
          take = true;
        } else {
          const Command h = resolve(head);
          bool second = false;
          take = if_condition(h, 1, second);
        }
      }
      if (take) return run_range(f, heads[b] + 1, heads[b + 1]);
    }
    return Flow::Normal;
  }
  if (action.empty()) fail(c, "action missing (THEN, EXIT, CYCLE, STOP or :label)");
  const bool known = action == "EXIT" || action == "CYCLE" || action == "STOP" || action[0] == ':';
  if (!known)
    fail(c, fmt::format("unknown action '{}' (THEN, EXIT, CYCLE, STOP or :label)", action));
  if (!cond) return Flow::Normal;
  if (action == "STOP") {
    Log::info("{}:{}: *IF: STOP: the run ends here", c.where.file, c.where.line);
    stopped_ = true;
    return Flow::Stop;
  }
  if (action == "EXIT" || action == "CYCLE") {
    if (f.loop_depth == 0) {
      warn(c, fmt::format("{} outside a *DO loop ignored", action));
      return Flow::Normal;
    }
    return action == "EXIT" ? Flow::Exit : Flow::Cycle;
  }
  f.jump_label = action;
  f.jump_from = i;
  f.jump_where = c.where;
  return Flow::Jump;
}

// ---- the loop over commands
// ----------------------------------------------------------------------

DeckReader::Flow DeckReader::run_range(Frame& f, std::size_t begin, std::size_t end) {
  Program& prog = f.program;
  const auto& cmds = prog.cmds;
  std::size_t i = begin;
  while (i < end) {
    if (f.loop_depth == 0 && prog.depth[i] == 0) prog.release_before(i);
    const RawCommand& raw = cmds[i];
    IMPACTFE_CHECK(!raw.released, "a released deck command reached again");
    if (raw.format_line) {  // consumed by its command; a stray one is skipped
      ++i;
      continue;
    }
    if (!raw.error.empty()) throw InputError(location_of(raw), raw.error);
    if (const auto e = prog.error.find(i); e != prog.error.end() && !e->second.empty())
      throw InputError(location_of(raw), e->second);
    Command c = resolve(raw);
    if (raw.star_comment)
      warn(c,
           "the text after a blank and '*' is a comment (MAPDL), ignored: write a product "
           "without the blank");
    std::size_t next = i + 1;
    while (next < end && cmds[next].format_line) c.format_lines.push_back(cmds[next++].rest);
    count_executed(c);
    if (!c.name.empty() && c.name[0] == ':') {  // a label
      i = next;
      continue;
    }
    const CommandSpec* spec = lookup(c);
    if (spec == nullptr && run_unknown(c, spec)) {
      if (stopped_) return Flow::Stop;
      i = next;
      continue;
    }
    // A repeat line re-issues a command's name with new fields; a block or control command
    // (*BEGIN, *DO, *IF, ...) takes its structure from the lines around it, which a repeat line
    // does not have.
    if (raw.repeat && spec->handler == nullptr)
      fail(c, fmt::format("a repeat line (leading comma) cannot repeat the control command {}; "
                          "write the command out",
                          c.name));
    last_name_ = c.name;
    const std::string& n = c.name;
    if (spec->handler != nullptr) {
      dispatch(c, *spec);
      if (n != "*REPEAT") last_command_ = c;
      i = next;
      continue;
    }
    // ---- control commands ----
    Flow flow = Flow::Normal;
    if (n == "*DO") {
      if (run_block_do(c)) {
        if (stopped_) return Flow::Stop;
        i = next;
        continue;
      }
      flow = run_do(f, i, c);
    } else if (n == "*DOWHILE") {
      flow = run_dowhile(f, i, c);
    } else if (n == "*IF") {
      flow = run_if(f, i, c);
    } else if (n == "*EXIT" || n == "*CYCLE") {
      if (f.loop_depth == 0)
        warn(c, fmt::format("{} outside a *DO loop ignored", n));
      else
        return n == "*EXIT" ? Flow::Exit : Flow::Cycle;
    } else if (n == "*GO") {
      const std::string target = label(c, 1);
      if (target.empty() || target[0] != ':') fail(c, "give the label as :NAME");
      f.jump_label = target;
      f.jump_from = i;
      f.jump_where = c.where;
      return Flow::Jump;
    } else if (n == "*BEGIN" || n == "*CREATE") {
      if (n == "*CREATE" && f.loop_depth > 0) fail(c, "*CREATE may not appear inside a *DO loop");
      const std::size_t close = prog.match[i];
      IMPACTFE_CHECK(close != kNone, "a *CREATE or *BEGIN block without its matched *END");
      record_block(c, std::vector<RawCommand>(cmds.begin() + static_cast<long>(i) + 1,
                                              cmds.begin() + static_cast<long>(close)));
      i = close + 1;
      continue;
    } else if (n == "*USE") {
      run_use(c);
    } else if (n == "/INPUT") {
      run_input(c);
    } else if (n == "/EOF") {
      return Flow::EndFile;
    } else if (n == "/EXIT") {
      // /EXIT,Slab: the run ends here. NOSAVE only: nothing is saved at the exit.
      const std::string slab = to_upper(trim(c.text(1)));
      if (slab != "NOSAVE")
        fail(c, fmt::format("saving the database at the exit ('{}') is not supported; give "
                            "/EXIT,NOSAVE (and SAVE before it)",
                            slab.empty() ? "MODEL" : slab));
      Log::info("{}:{}: /EXIT: the run ends here", c.where.file, c.where.line);
      stopped_ = true;
      return Flow::Stop;
    } else if (n == "*REPEAT") {
      repeat_previous(c);
    } else {
      fail(c, fmt::format("{} without a matching opening command", n));
    }
    if (stopped_) return Flow::Stop;
    if (flow != Flow::Normal) return flow;
    i = prog.match[i] != kNone && n != "*REPEAT" ? prog.match[i] + 1 : next;
  }
  return Flow::Normal;
}

}  // namespace impactfe::deck
