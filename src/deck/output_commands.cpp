// Output commands (APDL_SCRIPTING §A.9, §A.14; APDL_MODELING §10.4): *VWRITE, *MSG, *STATUS,
// *LIST, /OUTPUT, /COM, *CFOPEN, *CFWRITE, *CFCLOS. Printed text goes through the session's one
// OutputSink (or the *CFOPEN file for *VWRITE / *CFWRITE).
#include <fmt/format.h>

#include <filesystem>
#include <fstream>
#include <sstream>

#include "core/files.h"
#include "deck/deck_context.h"
#include "deck/output_format.h"

namespace impactfe::deck {

namespace {

constexpr std::size_t kMaxOutputLine = 128;  // *VWRITE lines are cut here (§A.9)
constexpr long long kMaxVwriteLines = 10'000'000;

/// A file name from Fname (field f) and Ext (field f+1): "Fname.Ext", "Fname", or the jobname
/// with `default_ext` when Fname is blank.
std::string file_name(DeckReader& r, const Command& c, int f, const std::string& default_ext) {
  std::string name = r.text_field(c, f);
  std::string ext = r.text_field(c, f + 1);
  if (name.empty()) {
    name = r.model.jobname;
    if (ext.empty()) ext = default_ext;
  }
  return ext.empty() ? name : name + "." + ext;
}

void write_line(DeckReader& r, const std::string& line) {
  if (r.scripting.command_file.stream.is_open()) {
    r.scripting.command_file.stream << line << '\n';
    r.scripting.command_file.stream.flush();
  } else {
    r.output.print(line);
  }
}

OutputFormat parse_format(DeckReader& r, const Command& c) {
  if (c.format_lines.empty()) r.fail(c, "format line missing (it is the line after the command)");
  std::string text;
  for (const auto& l : c.format_lines) text += l;
  try {
    return OutputFormat::parse(text);
  } catch (const FormatError& e) {
    r.fail(c, fmt::format("bad format '{}': {}", trim(text), e.what()));
  }
}

/// One *VWRITE data item: SEQU, an array column from a start element, or a value fixed when
/// the command is read.
struct VwriteItem {
  enum Kind { Sequence, Column, Constant } kind = Constant;
  ArrayPosition start;
  Value constant;
  long long length() const { return kind == Column ? start.param->imax - start.i + 1 : 0; }
  Value at(long long row) const {
    if (kind == Sequence) return static_cast<double>(row + 1);
    if (kind == Constant) return constant;
    const int i = start.i + static_cast<int>(row);
    if (i > start.param->imax)  // a shorter column pads with 0 / blanks (§A.9)
      return start.param->is_character_array() ? Value(std::string()) : Value(0.0);
    return start.param->entry(i, start.j, start.k);
  }
};

void cmd_vwrite(DeckReader& r, const Command& c) {
  const OutputFormat format = parse_format(r, c);
  std::vector<VwriteItem> items;
  for (int k = 1; k <= std::min(c.n_fields(), 19); ++k) {
    if (c.blank(k)) break;  // items after the first blank one are ignored
    VwriteItem item;
    const std::string& t = c.text(k);
    const auto n = split_subscripted_name(t);
    const Param* p = n ? r.params.find(n->name) : nullptr;
    if (to_upper(t) == "SEQU") {
      item.kind = VwriteItem::Sequence;
    } else if (p != nullptr && p->type == ParamType::StringArray) {
      // A STRING array element is one text (its row subscript is a character position).
      item.constant = r.value(c, k);
    } else if (p != nullptr && p->is_array()) {
      // Array elements are addressed by position (TABLE entries too, §A.7).
      item.kind = VwriteItem::Column;
      item.start = array_position(r, c, t);
    } else {
      item.constant = r.value(c, k);
    }
    items.push_back(std::move(item));
  }
  long long rows = items.empty() ? 1 : 0;
  bool any_column = false;
  for (const auto& it : items) {
    rows = std::max(rows, it.length());
    any_column = any_column || it.kind == VwriteItem::Column;
  }
  if (!any_column) rows = 1;
  VectorSettings& vs = r.scripting.vector_settings;
  if (vs.n_rows) rows = std::min<long long>(rows, *vs.n_rows);
  const std::string mask_name = vs.mask;
  const int row_step = std::max(vs.row_increment, 1);
  vs = VectorSettings{};
  if (rows > kMaxVwriteLines) r.fail(c, fmt::format("{} lines refused", rows));
  std::vector<std::string> warnings;
  bool cut = false;
  const ArrayPosition mask_pos =
      mask_name.empty() ? ArrayPosition{} : array_position(r, c, mask_name);
  for (long long row = 0; row < rows; row += row_step) {
    if (mask_pos.param != nullptr) {
      const int mi = mask_pos.i + static_cast<int>(row);
      if (mi <= mask_pos.param->imax &&
          mask_pos.param->values[mask_pos.param->offset(mi, mask_pos.j, mask_pos.k)] <= 0.0)
        continue;
    }
    std::vector<Value> values;
    values.reserve(items.size());
    for (const auto& it : items) values.push_back(it.at(row));
    for (std::string& line : format.format(values, &warnings)) {
      if (line.size() > kMaxOutputLine) {
        line.resize(kMaxOutputLine);
        cut = true;
      }
      write_line(r, line);
    }
  }
  if (cut) r.warn(c, fmt::format("output lines cut at {} characters", kMaxOutputLine));
  if (!warnings.empty()) r.warn(c, warnings.front());
}

void cmd_msg(DeckReader& r, const Command& c) {
  const std::string lab = c.blank(1) ? "INFO" : r.label(c, 1);
  const OutputFormat format = parse_format(r, c);
  std::vector<Value> values;
  for (int k = 2; k <= std::min(c.last_given(), 9); ++k) values.push_back(r.value(c, k));
  std::vector<std::string> warnings;
  const auto lines = format.format(values, &warnings);
  std::string message;
  for (const auto& l : lines) message += (message.empty() ? "" : "\n") + l;
  if (lab == "INFO" || lab == "UI") {
    r.output.print(message);
  } else if (lab == "NOTE") {
    r.output.print(" *** NOTE ***\n" + message);
  } else if (lab == "WARN") {
    r.output.print(" *** WARNING ***\n" + message);
    r.warn(c, message);
  } else if (lab == "ERROR" || lab == "FATAL") {
    r.output.print(" *** ERROR ***\n" + message);
    // A batch run ends at an error message; an empty one still tells the user why it stopped.
    r.fail(c, message.find_first_not_of(' ') == std::string::npos
                  ? fmt::format("*MSG,{} stopped the run (its message line is empty)", lab)
                  : message);
  } else {
    r.fail(c, fmt::format("unknown label '{}' (INFO NOTE WARN ERROR FATAL UI)", lab));
  }
}

std::string value_text(const Param& p) {
  if (p.type == ParamType::Number) return fmt::format("{:.8G}", p.number);
  if (p.type == ParamType::Text) return "'" + p.text + "'";
  return {};
}

std::string status_line(const std::string& name, const Param& p) {
  std::string dims;
  if (p.is_array()) dims = fmt::format("{:>8}{:>8}{:>8}", p.imax, p.jmax, p.kmax);
  return fmt::format(" {:<32} {:<24} {:<10}{}", name, value_text(p), param_type_name(p.type), dims);
}

void cmd_status(DeckReader& r, const Command& c) {
  // *STATUS,Par,IMIN,IMAX,JMIN,JMAX,KMIN,KMAX (§A.14): name-sorted, deterministic.
  const std::string par = r.label(c, 1);
  const std::string header = fmt::format(" {:<32} {:<24} {:<10}{:>8}{:>8}{:>8}", "NAME", "VALUE",
                                         "TYPE", "IMAX", "JMAX", "KMAX");
  // Par groups (MAPDL *STATUS): ALL, blank or PARM = every parameter but the local ones and
  // those whose names begin or end with '_'; _PRM / PRM_ = only those; ARGX = the locals.
  if (par.empty() || par == "ALL" || par == "PARM" || par == "ARGX" || par == "_PRM" ||
      par == "PRM_") {
    const auto& table = par == "ARGX" ? r.params.locals() : r.params.all();
    auto listed = [&](const std::string& name) {
      if (par == "_PRM") return name.front() == '_';
      if (par == "PRM_") return name.back() == '_';
      return name.front() != '_' && name.back() != '_';
    };
    std::vector<std::string> lines;
    for (const auto& [name, p] : table)
      if (listed(name)) lines.push_back(status_line(name, p));
    r.output.print(fmt::format(" PARAMETER STATUS- {} ({} PARAMETERS DEFINED)",
                               par == "ARGX"                    ? "LOCAL (ARGX)"
                               : par == "_PRM" || par == "PRM_" ? par
                                                                : "",
                               lines.size()));
    r.output.print(header);
    for (const auto& l : lines) r.output.print(l);
    return;
  }
  const Param* p = r.params.find(par);
  if (p == nullptr) r.fail(c, fmt::format("parameter {} is not defined", par));
  r.output.print(fmt::format(" PARAMETER STATUS- {}", par));
  r.output.print(header);
  r.output.print(status_line(par, *p));
  if (!p->is_array()) return;
  auto range = [&](int f, int lo, int hi, int& a, int& b) {
    a = std::max(r.integer(c, f, lo), lo);
    b = std::min(r.integer(c, f + 1, hi), hi);
  };
  int i0, i1, j0, j1, k0, k1;
  range(2, p->low(), p->imax, i0, i1);
  range(4, p->low(), p->jmax, j0, j1);
  range(6, p->low(), p->kmax, k0, k1);
  r.output.print(fmt::format(" {:>8}{:>8}{:>8}   {}", "I", "J", "K", "VALUE"));
  for (int k = k0; k <= k1; ++k)
    for (int j = j0; j <= j1; ++j)
      for (int i = i0; i <= i1; ++i) {
        const Value v = p->entry(i, j, k);
        r.output.print(fmt::format(
            " {:>8}{:>8}{:>8}   {}", i, j, k,
            is_text(v) ? std::get<std::string>(v) : fmt::format("{:.8G}", std::get<double>(v))));
      }
}

void cmd_list(DeckReader& r, const Command& c) {
  // *LIST,Fname,Ext: a *CREATE file in memory first, then a file on disk.
  const std::string name = file_name(r, c, 1, "");
  if (name.empty()) r.fail(c, "file name missing");
  if (auto it = r.scripting.files.find(to_upper(name)); it != r.scripting.files.end()) {
    for (const auto& l : it->second.lines) r.output.print(l);
    return;
  }
  std::string path = name;
  const std::string beside = resolve_input(c.where.file, name, "");
  if (!file_exists(path) && file_exists(beside)) path = beside;
  std::optional<std::string> text;
  try {
    text = read_file(path, ReadLimits::bytes());
  } catch (const OversizedFileError& e) {
    r.fail(c, e.what());
  }
  if (!text) r.fail(c, fmt::format("file '{}' not found", name));
  std::istringstream in(*text);
  for (std::string line; std::getline(in, line);) r.output.print(line);
}

void cmd_output(DeckReader& r, const Command& c) {
  // /OUTPUT,Fname,Ext,--,Loc: blank (or TERM) = back to the terminal; APPEND appends.
  const std::string fname = r.text_field(c, 1);
  if ((fname.empty() && c.blank(2)) || to_upper(fname) == "TERM") {
    r.output.to_terminal();
    return;
  }
  const std::string path = file_name(r, c, 1, "");
  const std::string loc = r.label(c, 4);
  if (!loc.empty() && loc != "APPEND") r.fail(c, fmt::format("Loc '{}': blank or APPEND", loc));
  try {
    r.output.redirect(path, loc == "APPEND");
  } catch (const std::runtime_error& e) {
    r.fail(c, e.what());
  }
  Log::info("{}:{}: /OUTPUT: output goes to {}", c.where.file, c.where.line, path);
}

void cmd_delete(DeckReader& r, const Command& c) {
  // /DELETE,Fname,Ext: the *CREATE file in memory and the file on disk; a missing file is a note
  // (APDL_SCRIPTING §A.14).
  const std::string name = file_name(r, c, 1, "");
  if (name.empty()) r.fail(c, "file name missing");
  if (r.output.redirected() && r.output.file() == name)
    r.fail(c, fmt::format("'{}' is the open /OUT file (/OUT back to the terminal first)", name));
  if (r.scripting.command_file.stream.is_open() && r.scripting.command_file.path == name)
    r.fail(c, fmt::format("'{}' is the open *CFOPEN file (*CFCLOS first)", name));
  const bool in_memory = r.scripting.files.erase(to_upper(name)) != 0;
  std::error_code ec;
  const bool on_disk = std::filesystem::remove(name, ec);
  if (ec) r.fail(c, fmt::format("cannot delete '{}': {}", name, ec.message()));
  if (!in_memory && !on_disk)
    Log::info("{}:{}: /DELETE: no file '{}' to delete", c.where.file, c.where.line, name);
}

void cmd_com(DeckReader& r, const Command& c) {
  Log::info("{}:{}: /COM {}", c.where.file, c.where.line, c.rest);
  r.output.print(" " + c.rest);
}

void cmd_cfopen(DeckReader& r, const Command& c) {
  // *CFOPEN,Fname,Ext,--,Loc: Fname blank → jobname.CMD; one file at a time.
  const std::string path = file_name(r, c, 1, "cmd");
  const std::string loc = r.label(c, 4);
  if (!loc.empty() && loc != "APPEND") r.fail(c, fmt::format("Loc '{}': blank or APPEND", loc));
  if (r.scripting.command_file.stream.is_open()) r.scripting.command_file.stream.close();
  r.scripting.command_file.stream.clear();
  r.scripting.command_file.stream.open(path, loc == "APPEND" ? std::ios::app : std::ios::trunc);
  if (!r.scripting.command_file.stream) {
    r.scripting.command_file.stream.close();
    r.fail(c, fmt::format("cannot open '{}' for writing", path));
  }
  r.scripting.command_file.path = path;
}

void cmd_cfwrite(DeckReader& r, const Command& c) {
  // *CFWRITE,Command: the command written as one line, its parameter fields replaced by their
  // values (free format) and %...% substituted.
  if (!r.scripting.command_file.stream.is_open()) r.fail(c, "no command file open (*CFOPEN first)");
  std::string line = c.rest;
  if (c.fields.size() > 1) {  // a single field (`*CFWRITE,A = 5`) is written as it stands
    line = c.fields[0];
    for (std::size_t k = 1; k < c.fields.size(); ++k) {
      const std::string& f = c.fields[k];
      std::string out = f;
      if (!f.empty() && f.front() != '\'' && !parse_fortran_number(f)) {
        try {
          const Value v = r.evaluate_expression(f);
          out = is_text(v) ? std::get<std::string>(v) : format_number(std::get<double>(v));
        } catch (const ExpressionError&) {
          out = f;  // a label (UX, ALL, ...)
        }
      }
      line += "," + out;
    }
  }
  r.scripting.command_file.stream << line << '\n';
  r.scripting.command_file.stream.flush();
}

void cmd_cfclos(DeckReader& r, const Command& c) {
  if (!r.scripting.command_file.stream.is_open()) {
    r.warn(c, "no command file is open");
    return;
  }
  r.scripting.command_file.stream.close();
  r.scripting.command_file.path.clear();
}

}  // namespace

void write_output(DeckReader& r, const std::string& text) {
  r.output.write(text);
}

void register_output_commands(std::vector<CommandSpec>& t) {
  t.push_back({"*VWRITE", cmd_vwrite, kAnywhere});
  t.push_back({"*MSG", cmd_msg, kAnywhere});
  t.push_back({"*STATUS", cmd_status, kAnywhere});
  t.push_back({"*LIST", cmd_list, kAnywhere});
  t.push_back({"/OUTPUT", cmd_output, kAnywhere});
  t.push_back({"/OUT", cmd_output, kAnywhere});
  t.push_back({"/COM", cmd_com, kAnywhere});
  t.push_back({"/DELETE", cmd_delete, kAnywhere});
  t.push_back({"*CFOPEN", cmd_cfopen, kAnywhere});
  t.push_back({"*CFWRITE", cmd_cfwrite, kAnywhere});
  t.push_back({"*CFCLOS", cmd_cfclos, kAnywhere});
}

}  // namespace impactfe::deck
