// Files, macros and blocks (APDL_SCRIPTING §A.12–§A.13): /INPUT, *CREATE files and *USE, macros
// run by an unknown command name, and the 4x *BEGIN blocks that *DO replays. The executor that
// runs their commands is in control_flow.cpp.
#include <fmt/format.h>

#include <filesystem>

#include "core/files.h"
#include "deck/deck_context.h"

namespace impactfe::deck {

namespace {

std::string directory_of(const std::string& path) {
  return std::filesystem::path(path).parent_path().string();
}

std::string join_path(const std::string& dir, const std::string& name) {
  if (dir.empty() || std::filesystem::path(name).is_absolute()) return name;
  return (std::filesystem::path(dir) / name).string();
}

}  // namespace

// ---- files -------------------------------------------------------------------------------------

std::string read_text_file(const std::string& path, const SourceLocation& where) {
  std::optional<std::string> text;
  try {
    text = read_file(path, ReadLimits::text());  // rank 0's disk under MPI (core/files.h)
  } catch (const OversizedFileError& e) {
    // Located at the offending line of the file itself, else at the /INPUT that names it.
    if (e.line() > 0)
      throw InputError(
          SourceLocation{path, e.line(), "(line)"},
          fmt::format("line longer than {} bytes refused (is it a text file?)", e.limit()));
    throw InputError(where, fmt::format("'{}' is larger than {} bytes: refused", path, e.limit()));
  }
  if (!text) {
    if (where.known()) throw InputError(where, fmt::format("cannot open input file '{}'", path));
    throw InputError(fmt::format("cannot open deck '{}'", path));
  }
  return std::move(*text);
}

std::string resolve_input(const std::string& includer, const std::string& fname,
                          const std::string& ext, const std::string& dir_field) {
  const std::string dir =
      dir_field.empty() ? directory_of(includer) : join_path(directory_of(includer), dir_field);
  const std::string name = ext.empty() ? fname : fname + "." + ext;
  const std::string path = join_path(dir, name);
  if (!ext.empty() || file_exists(path, true)) return path;
  for (const char* e : {".inp", ".mac"}) {
    const std::string alt = join_path(dir, fname + e);
    if (file_exists(alt, true)) return alt;
  }
  return path;
}

void DeckReader::run_file(const std::string& path, const SourceLocation& where) {
  const auto text = std::make_shared<const std::string>(read_text_file(path, where));
  // A CDB archive tests MAPDL's flag _CDRDOFF (1 only after CDREAD read a solid model first,
  // which never happens here): 0 unless the deck set it.
  std::string ext = std::filesystem::path(path).extension().string();
  if (to_upper(ext) == ".CDB" && params.find("_CDRDOFF") == nullptr) params.set("_CDRDOFF", 0.0);
  auto cmds = lex_text(*text, path, dialect, text);
  std::error_code ec;
  const auto canonical = std::filesystem::weakly_canonical(path, ec);
  run_program(cmds, "file " + (ec ? path : canonical.string()), where);
}

void DeckReader::run_text(const std::string& text, const std::string& path) {
  run_shared_text(std::make_shared<const std::string>(text), path);
}

void DeckReader::run_shared_text(const std::shared_ptr<const std::string>& text,
                                 const std::string& path) {
  auto cmds = lex_text(*text, path, dialect, text);
  std::error_code ec;
  const auto canonical = std::filesystem::weakly_canonical(path, ec);
  run_program(cmds, "file " + (ec ? path : canonical.string()), SourceLocation{});
}

void DeckReader::run_input(const Command& c) {
  if (c.blank(1)) fail(c, "file name missing");
  if (dialect == Dialect::Classic4x && trim(c.text(1)) == "27") {
    run_frozen_analysis(*this, c);
    return;
  }
  if (!c.blank(4) && real(c, 4, 0.0) != 0.0)
    fail(c, "LINE (start at a line or label) is not supported");
  run_file(resolve_input(c.where.file, text_field(c, 1), text_field(c, 2), text_field(c, 3)),
           c.where);
}

// ---- macros and blocks -------------------------------------------------------------------------

bool DeckReader::call_macro(const Command& c, const std::string& name,
                            const std::vector<Value>& args) {
  const std::string key = to_upper(name);
  std::vector<RawCommand> cmds;
  std::string frame_name;
  if (auto it = scripting.files.find(key); it != scripting.files.end()) {
    cmds = it->second.commands;  // a copy: the macro may *CREATE itself anew
    frame_name = "macro " + key;
  } else if (auto it2 = scripting.files.find(key + ".MAC"); it2 != scripting.files.end()) {
    cmds = it2->second.commands;
    frame_name = "macro " + key + ".MAC";
  } else {
    std::string path;
    const std::string lower = to_lower(name);
    for (const std::string& dir : {directory_of(c.where.file), std::string()})
      for (const std::string& candidate :
           {name, name + ".mac", lower, lower + ".mac", name + ".MAC"}) {
        const std::string p = join_path(dir, candidate);
        if (path.empty() && file_exists(p)) path = p;
      }
    if (path.empty()) return false;
    cmds = lex_text(read_text_file(path, c.where), path, dialect);
    std::error_code ec;
    const auto canonical = std::filesystem::weakly_canonical(path, ec);
    frame_name = "file " + (ec ? path : canonical.string());
  }
  params.push_level();
  try {
    for (std::size_t k = 0; k < args.size() && k < 19; ++k) {
      const std::string arg = k < 9 ? fmt::format("ARG{}", k + 1) : fmt::format("AR{}", k + 1);
      if (is_text(args[k]))
        params.set_text(arg, std::get<std::string>(args[k]));
      else
        params.set(arg, std::get<double>(args[k]));
    }
    run_program(cmds, frame_name, c.where);
  } catch (...) {
    params.pop_level();
    throw;
  }
  params.pop_level();
  return true;
}

void DeckReader::run_block_macro(const Command& c, const std::string& name) {
  auto cmds = scripting.macros.at(name);  // copy: the block may redefine itself
  run_program(cmds, "block " + name, c.where);
}

void DeckReader::record_block(const Command& c, std::vector<RawCommand> body) {
  const std::string& n = c.name;
  const std::string name = label(c, 1);
  if (name.empty()) fail(c, "name missing");
  const std::size_t count = body.size();
  if (n == "*BEGIN") {
    scripting.macros[name] = std::move(body);
  } else {
    const std::string ext = label(c, 2);
    MacroFile& file = scripting.files[ext.empty() ? name : name + "." + ext];
    file.lines.clear();
    int last_line = -1;
    for (const auto& b : body)
      if (b.line != last_line) {
        file.lines.push_back(b.source);
        last_line = b.line;
      }
    file.commands = std::move(body);
  }
  Log::info("{}:{}: {}: {} recorded ({} commands)", c.where.file, c.where.line, n, name, count);
}

void DeckReader::run_use(const Command& c) {
  const std::string name = text_field(c, 1);
  if (name.empty()) fail(c, "macro name missing");
  std::vector<Value> args;
  for (int k = 2; k <= c.n_fields() && k <= 19; ++k) args.push_back(value(c, k));
  if (!call_macro(c, name, args))
    fail(c, fmt::format("macro '{}' not found (*CREATE it, or a file {} / {}.mac)", name, name,
                        to_lower(name)));
}

bool DeckReader::run_block_do(const Command& c) {
  const std::string block = label(c, 1);
  if (dialect != Dialect::Classic4x || scripting.macros.count(block) == 0) return false;
  // 4x *DO,Block,N1,N2: the *BEGIN block once per k = N1..N2; after each pass every parameter
  // with a *SET increment is incremented (APDL_SUBSET §3.29).
  const int n1 = integer(c, 2, 1);
  const int n2 = integer(c, 3, n1);
  if (static_cast<long long>(n2) - n1 + 1 > kMaxLoopTrips) fail(c, "too many passes");
  for (int k = n1; k <= n2; ++k) {
    count_executed(c);
    run_block_macro(c, block);
    if (stopped_) return true;
    for (const auto& [name, inc] : scripting.increments)
      params.set(name, params.get(name).value_or(0.0) + inc);
  }
  return true;
}

// ---- unknown command names ---------------------------------------------------------------------

bool DeckReader::run_unknown(Command& c, const CommandSpec*& spec) {
  // MAPDL's unknown-command macro: NAME.MAC (in memory or on disk) run with the fields as
  // ARG1..AR19.
  bool is_macro = scripting.files.count(c.name + ".MAC") != 0;
  if (!is_macro) {
    const std::string lower = to_lower(c.name) + ".mac";
    is_macro = file_exists(join_path(directory_of(c.where.file), lower)) ||
               file_exists(join_path(directory_of(c.where.file), c.name + ".MAC")) ||
               file_exists(lower);
  }
  last_name_ = c.name;
  if (is_macro) {
    std::vector<Value> args;
    for (int k = 1; k <= c.n_fields() && k <= 19; ++k) args.push_back(value(c, k));
    call_macro(c, c.name + ".MAC", args) || call_macro(c, c.name, args);
    return true;
  }
  if (dialect == Dialect::Modern) {
    if (const CommandSpec* longer = find_command_by_longer_spelling(c.name)) {
      Log::info("{}:{}: {}: taken as {} (the first four characters)", c.where.file, c.where.line,
                c.name, longer->name);
      c.name = longer->name;
      c.where.command = c.name;
      spec = longer;
      return false;
    }
  }
  if (!options.skip_unknown) fail(c, "unknown command");
  if (!cannot_change_results(c.name))
    fail(c,
         "unknown command (--skip-unknown skips only graphics, printing and GUI commands, "
         "which cannot change the results; this one may)");
  warn(c, "unknown command skipped (--skip-unknown: graphics, printing or GUI only)");
  job.ignored_commands.push_back(
      fmt::format("{}:{}: {} (unknown)", c.where.file, c.where.line, c.name));
  auto& entry = skipped[c.name];
  if (entry.first++ == 0) entry.second = c.where;
  return true;
}

}  // namespace impactfe::deck
