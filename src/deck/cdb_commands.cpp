// The blocks of a CDB archive (what MAPDL's CDWRITE writes and CDREAD reads; Workbench input
// files use the same blocks in lower case): NBLOCK (nodes), EBLOCK (elements), CMBLOCK
// (components), RLBLOCK (real constant sets), and CDREAD itself. The lexer hands each block's
// format line(s) and fixed-column records to its handler (RawCommand::block), which reads them
// in one pass: a 10⁶-node archive is not interpreted line by line.
#include <fmt/format.h>

#include <algorithm>
#include <cctype>
#include <charconv>
#include <cmath>
#include <filesystem>
#include <fstream>
#include <set>
#include <sstream>
#include <string>
#include <string_view>
#include <vector>

#include "core/text.h"
#include "deck/cdb_format.h"
#include "deck/cdb_writer.h"
#include "deck/deck_context.h"
#include "elements/element_registry.h"

namespace impactfe::deck {

namespace {

/// The records of a block: its lines after the format line(s), with their line numbers.
class BlockRecords {
 public:
  BlockRecords(DeckReader& r, const Command& c, int n_formats) : r_(r), c_(c) {
    if (!c.block) r.fail(c, "the block's format line and records are missing");
    text_ = *c.block;
    line_ = c.block_line;
    for (int k = 0; k < n_formats; ++k) {
      std::string_view format;
      if (!next(format) || format.empty() || format.front() != '(')
        r.fail(c, fmt::format("format line {} of the block missing", k + 1));
      formats_.emplace_back(format);
    }
  }
  const std::string& format(int k) const { return formats_.at(static_cast<std::size_t>(k)); }
  /// The next record; false at the end of the block.
  bool next(std::string_view& record) {
    if (pos_ >= text_.size()) return false;
    std::size_t end = text_.find('\n', pos_);
    if (end == std::string_view::npos) end = text_.size();
    record = text_.substr(pos_, end - pos_);
    pos_ = end + 1;
    ++line_;
    return true;
  }
  /// A command naming the record's line, for messages.
  Command at_record() const {
    Command here = c_;
    here.where.line = line_ - 1;
    return here;
  }
  [[noreturn]] void fail(const std::string& message) const { r_.fail(at_record(), message); }

 private:
  DeckReader& r_;
  const Command& c_;
  std::string_view text_;
  std::size_t pos_ = 0;
  int line_ = 0;
  std::vector<std::string> formats_;
};

/// The integer of a fixed-width column ("" = 0); fails on anything else.
long long column_int(const BlockRecords& b, std::string_view text) {
  std::size_t i = 0, e = text.size();
  while (i < e && text[i] == ' ') ++i;
  while (e > i && (text[e - 1] == ' ' || text[e - 1] == '\r')) --e;
  if (i == e) return 0;
  long long v = 0;
  const auto [ptr, ec] = std::from_chars(text.data() + i, text.data() + e, v);
  if (ec != std::errc() || ptr != text.data() + e)
    b.fail(fmt::format("'{}' is not an integer", text.substr(i, e - i)));
  return v;
}

/// The real of a fixed-width column ("" = 0); Fortran exponents (1.0D3, 1.0-003) accepted.
double column_real(const BlockRecords& b, std::string_view text) {
  const std::string_view t = trim_view(text);
  if (t.empty()) return 0.0;
  if (const auto v = parse_fortran_number(t)) return *v;
  b.fail(fmt::format("'{}' is not a number", t));
}

/// The fields of a record by the format's columns into `out`; a short record leaves the rest
/// blank.
void split_columns(std::string_view record, const std::vector<int>& widths,
                   std::vector<std::string_view>& out) {
  out.clear();
  std::size_t pos = 0;
  for (int w : widths) {
    out.push_back(pos < record.size() ? record.substr(pos, static_cast<std::size_t>(w))
                                      : std::string_view());
    pos += static_cast<std::size_t>(w);
  }
}

std::vector<std::string_view> columns(std::string_view record, const std::vector<int>& widths) {
  std::vector<std::string_view> out;
  split_columns(record, widths, out);
  return out;
}

std::vector<int> format_widths(const BlockRecords& b, int k) {
  try {
    return field_widths(parse_fortran_format(b.format(k)));
  } catch (const std::invalid_argument& e) {
    b.fail(e.what());
  }
}

// NBLOCK,NUMFIELD,Solkey,NDMAX,NDSEL: node, (solid-model entity, line location when SOLID),
// then X, Y, Z, THXY, THYZ, THZX in global Cartesian; trailing blank values are 0.
void cmd_nblock(DeckReader& r, const Command& c) {
  const int n_reals = r.integer(c, 1, 3);
  if (n_reals < 3 || n_reals > 6) r.fail(c, fmt::format("NUMFIELD {}: 3 to 6", n_reals));
  const bool solid = r.label(c, 2) == "SOLID";
  BlockRecords b(r, c, 1);
  const std::vector<int> widths = format_widths(b, 0);
  const std::size_t n_ints = solid ? 3 : 1;
  if (widths.size() < n_ints + 3) b.fail("the format has fewer than the node's columns");
  std::string_view record;
  std::vector<Node> nodes;
  std::vector<std::string_view> col;
  while (b.next(record)) {
    const std::string_view t = trim_view(record);
    if (t == "-1" || t.rfind("N,", 0) == 0 || t.rfind("n,", 0) == 0) break;  // the end of the block
    split_columns(record, widths, col);
    Node n;
    const long long id = column_int(b, col[0]);
    if (id <= 0 || id > kMaxEntityNumber) b.fail(fmt::format("node number {} out of range", id));
    n.id = static_cast<int>(id);
    double v[6] = {0, 0, 0, 0, 0, 0};
    for (std::size_t k = 0; k < 6 && n_ints + k < col.size(); ++k)
      v[k] = column_real(b, col[n_ints + k]);
    n.x = Vec3(v[0], v[1], v[2]);
    n.angles_deg = Vec3(v[3], v[4], v[5]);
    nodes.push_back(n);
  }
  check_model_size(r, c, static_cast<long long>(nodes.size()), 0);
  for (const Node& n : nodes) r.model.nodes[n.id] = n;
}

/// Sets the attribute pointers for the elements of an EBLOCK and restores them afterwards.
class AttributeScope {
 public:
  explicit AttributeScope(DeckReader& r) : r_(r), saved_(r.modeling) {}
  ~AttributeScope() {
    r_.modeling.current_type = saved_.current_type;
    r_.modeling.current_real = saved_.current_real;
    r_.modeling.current_mat = saved_.current_mat;
    r_.modeling.current_secnum = saved_.current_secnum;
    r_.modeling.esys = saved_.esys;
  }
  AttributeScope(const AttributeScope&) = delete;
  AttributeScope& operator=(const AttributeScope&) = delete;

 private:
  DeckReader& r_;
  ModelingState saved_;
};

/// Checks an EBLOCK record's element coordinate system (0 or a local system above 10).
void check_element_esys(const BlockRecords& b, long long esys) {
  if (esys != 0 && esys <= 10)
    b.fail(fmt::format("ESYS {}: 0 or a local coordinate system above 10", esys));
}

// EBLOCK,NUM_NODES,,NDMAX,NDSEL without SOLID (the format MAPDL and Workbench write for contact,
// target and other elements without solid-model data): element number, TYPE, REAL, MAT, ESYS,
// then up to ten nodes; the record's blank columns end the node list, and an element type with
// more than ten nodes continues on the next record. A -1 record ends the block.
void eblock_nonsolid(DeckReader& r, const Command& c) {
  BlockRecords b(r, c, 1);
  const std::vector<int> widths = format_widths(b, 0);
  if (widths.size() < 6) b.fail("the format has fewer than the 5 columns before the nodes");
  AttributeScope scope(r);
  const std::vector<int> more_widths(widths.size(), widths.front());  // continuation records
  std::string_view record;
  long long count = 0;
  std::vector<std::string_view> col, more;
  while (b.next(record)) {
    split_columns(record, widths, col);
    const long long id = column_int(b, col[0]);
    if (id < 0) break;  // the -1 record ends the block
    if (id == 0 || id > kMaxEntityNumber) b.fail(fmt::format("element number {} out of range", id));
    const long long esys = column_int(b, col[4]);
    check_element_esys(b, esys);
    r.modeling.current_type = static_cast<int>(column_int(b, col[1]));
    r.modeling.current_real = static_cast<int>(column_int(b, col[2]));
    r.modeling.current_mat = static_cast<int>(column_int(b, col[3]));
    r.modeling.esys = static_cast<int>(esys);
    const auto type = r.model.element_types.find(r.modeling.current_type);
    if (type == r.model.element_types.end())
      b.fail(fmt::format("element type {} is not defined (ET missing before the EBLOCK)",
                         r.modeling.current_type));
    const int max_nodes = element_type_descriptor(type->second).max_nodes();
    std::vector<int> nodes;
    auto read_nodes = [&](const std::vector<std::string_view>& fields, std::size_t first) {
      std::size_t k = first;
      for (; k < fields.size() && !trim_view(fields[k]).empty(); ++k)
        nodes.push_back(static_cast<int>(column_int(b, fields[k])));
      return k == fields.size();  // every column filled: the list may continue
    };
    bool full = read_nodes(col, 5);
    while (full && static_cast<int>(nodes.size()) < max_nodes && b.next(record)) {
      split_columns(record, more_widths, more);
      full = read_nodes(more, 0);
    }
    if (nodes.empty()) b.fail(fmt::format("element {} has no nodes", id));
    check_target_shape(r, b.at_record(), nodes);
    if (r.model.elements.count(static_cast<int>(id)) == 0) check_model_size(r, c, 0, 1);
    r.add_element(b.at_record(), static_cast<int>(id), std::move(nodes));
    ++count;
  }
  if (count == 0) r.warn(c, "the block defines no element");
}

// EBLOCK,NUM_NODES,Solkey,NDMAX,NDSEL (solid format): MAT, TYPE, REAL, SECNUM, ESYS, birth/death,
// solid-model reference, shape, number of nodes, (unused), element number, 8 nodes per record
// line, further nodes on continuation lines; a -1 record ends the block.
void cmd_eblock(DeckReader& r, const Command& c) {
  if (c.blank(2)) {
    eblock_nonsolid(r, c);
    return;
  }
  if (r.label(c, 2) != "SOLID")
    r.fail(c, fmt::format("Solkey '{}': SOLID or blank (the non-solid format)", r.label(c, 2)));
  BlockRecords b(r, c, 1);
  const std::vector<int> widths = format_widths(b, 0);
  if (widths.size() < 11) b.fail("the format has fewer than the 11 columns before the nodes");
  AttributeScope scope(r);
  const std::vector<int> more_widths(widths.size(), widths.front());  // continuation records
  std::string_view record;
  long long count = 0;
  std::vector<std::string_view> col, more;
  while (b.next(record)) {
    split_columns(record, widths, col);
    const long long mat = column_int(b, col[0]);
    if (mat < 0) break;  // the -1 record ends the block
    const long long esys = column_int(b, col[4]), dead = column_int(b, col[5]);
    const long long n_nodes = column_int(b, col[8]), id = column_int(b, col[10]);
    check_element_esys(b, esys);
    if (dead != 0) b.fail("killed elements (birth/death flag) are not supported");
    if (n_nodes < 1 || n_nodes > 64) b.fail(fmt::format("{} nodes per element", n_nodes));
    if (id <= 0 || id > kMaxEntityNumber) b.fail(fmt::format("element number {} out of range", id));
    std::vector<int> nodes;
    for (std::size_t k = 11; k < col.size() && static_cast<long long>(nodes.size()) < n_nodes; ++k)
      nodes.push_back(static_cast<int>(column_int(b, col[k])));
    while (static_cast<long long>(nodes.size()) < n_nodes && b.next(record)) {
      split_columns(record, more_widths, more);
      for (std::size_t k = 0; k < more.size() && static_cast<long long>(nodes.size()) < n_nodes;
           ++k)
        nodes.push_back(static_cast<int>(column_int(b, more[k])));
    }
    r.modeling.current_mat = static_cast<int>(mat);
    r.modeling.current_type = static_cast<int>(column_int(b, col[1]));
    r.modeling.current_real = static_cast<int>(column_int(b, col[2]));
    r.modeling.current_secnum = static_cast<int>(column_int(b, col[3]));
    r.modeling.esys = static_cast<int>(esys);
    if (r.model.elements.count(static_cast<int>(id)) == 0) check_model_size(r, c, 0, 1);
    r.add_element(b.at_record(), static_cast<int>(id), std::move(nodes));
    ++count;
  }
  if (count == 0) r.warn(c, "the block defines no element");
}

// CMBLOCK,Cname,Entity,NUMITEMS: the ids in the format's columns; a negative id ends a range
// begun by the one before it (17, -18 = 17..18).
void cmd_cmblock(DeckReader& r, const Command& c) {
  const std::string name = r.label(c, 1), entity = r.label(c, 2);
  if (name.empty()) r.fail(c, "component name missing");
  if (entity != "NODE" && entity != "ELEM")
    r.fail(c, fmt::format("Entity '{}': NODE or ELEM (solid-model components are not read from "
                          "a CDB)",
                          entity));
  const long long n_items = r.integer(c, 3, 0);
  BlockRecords b(r, c, 1);
  const std::vector<int> widths = format_widths(b, 0);
  auto defined = [&](int id) {
    return entity == "NODE" ? r.model.nodes.count(id) != 0 : r.model.elements.count(id) != 0;
  };
  std::vector<int> ids;
  long long read = 0;
  std::string_view record;
  while (read < n_items && b.next(record)) {
    for (const auto& col : columns(record, widths)) {
      if (read == n_items || trim_view(col).empty()) break;
      const long long v = column_int(b, col);
      ++read;
      if (v < 0) {
        if (ids.empty() || -v < ids.back()) b.fail(fmt::format("range end {} without a start", v));
        // A range holds defined entities only: it stops at the first one that is not.
        for (long long k = ids.back() + 1; k <= -v; ++k) {
          if (!defined(static_cast<int>(k)))
            b.fail(fmt::format("{} {} of component {} is not defined", entity, k, name));
          ids.push_back(static_cast<int>(k));
        }
      } else {
        ids.push_back(static_cast<int>(v));
      }
    }
  }
  if (read != n_items) b.fail(fmt::format("{} of NUMITEMS {} ids given", read, n_items));
  std::sort(ids.begin(), ids.end());
  ids.erase(std::unique(ids.begin(), ids.end()), ids.end());
  for (int id : ids)
    if (!defined(id))
      r.fail(c, fmt::format("{} {} of component {} is not defined", entity, id, name));
  r.model.components[name] = Component{entity, std::move(ids), c.where};
}

// RLBLOCK,NSET,MAXSET,MAXITEMS,NPERLN: per set a record with its number, its count of values
// and the first values, then continuation records of NPERLN values.
void cmd_rlblock(DeckReader& r, const Command& c) {
  const long long n_sets = r.integer(c, 1, 0);
  BlockRecords b(r, c, 2);
  const std::vector<int> first = format_widths(b, 0), more = format_widths(b, 1);
  if (first.size() < 3) b.fail("the first format needs the set number, the count and values");
  std::string_view record;
  for (long long s = 0; s < n_sets; ++s) {
    if (!b.next(record)) b.fail(fmt::format("{} of NSET {} sets given", s, n_sets));
    const auto col = columns(record, first);
    RealSet set;
    const long long id = column_int(b, col[0]), n = column_int(b, col[1]);
    if (id <= 0 || id > kMaxEntityNumber)
      b.fail(fmt::format("real set number {} out of range", id));
    if (n < 0 || n > 100000) b.fail(fmt::format("{} values in set {}", n, id));
    set.id = static_cast<int>(id);
    for (std::size_t k = 2; k < col.size() && static_cast<long long>(set.values.size()) < n; ++k)
      set.values.push_back(column_real(b, col[k]));
    while (static_cast<long long>(set.values.size()) < n) {
      if (!b.next(record))
        b.fail(fmt::format("set {}: {} of {} values given", id, set.values.size(), n));
      for (const auto& v : columns(record, more))
        if (static_cast<long long>(set.values.size()) < n) set.values.push_back(column_real(b, v));
    }
    r.model.real_sets[set.id] = std::move(set);
  }
}

// NUMOFF,Label,VALUE: adds VALUE to the numbers of the entities already defined, so that an
// archive read next does not overwrite them. A CDB archive issues it before its own entities;
// on a database without such entities it changes nothing.
void cmd_numoff(DeckReader& r, const Command& c) {
  const std::string label = r.label(c, 1);
  const int value = r.integer(c, 2, 0);
  if (value < 0) r.fail(c, fmt::format("VALUE {} must not be negative", value));
  const Model& m = r.model;
  bool any = false;
  if (label == "NODE")
    any = !m.nodes.empty();
  else if (label == "ELEM")
    any = !m.elements.empty();
  else if (label == "MAT")
    any = !m.materials.empty();
  else if (label == "TYPE")
    any = !m.element_types.empty();
  else if (label == "REAL")
    any = !m.real_sets.empty();
  else if (label == "SECN")
    any = !m.sections.empty();
  else if (label == "CSYS" || label == "KP" || label == "LINE" || label == "AREA" ||
           label == "VOLU" || label == "CP" || label == "CE")
    any = false;  // checked below where the model has them
  else
    r.fail(c, fmt::format("Label '{}' not supported (NODE, ELEM, MAT, TYPE, REAL, SECN, CSYS, KP, "
                          "LINE, AREA, VOLU, CP, CE)",
                          label));
  if (label == "CSYS")
    any = !r.model.coordinate_systems.systems().empty() &&
          r.model.coordinate_systems.systems().rbegin()->first > 10;  // local systems: 11 and up
  if (label == "KP") any = !m.solid.keypoints.empty();
  if (label == "LINE") any = !m.solid.lines.empty();
  if (label == "AREA") any = !m.solid.areas.empty();
  if (label == "VOLU") any = !m.solid.volumes.empty();
  if (any && value > 0)
    r.fail(c, fmt::format("renumbering the {} entities already defined is not supported: read the "
                          "archive into a database without them (/CLEAR first)",
                          label));
}

/// The file `name` in `directory`, its name compared without regard to case when no file has it
/// exactly (an archive CDWRITE wrote as VM193A.CDB and a deck reading vm193a.cdb: MAPDL's file
/// names are case-insensitive on Windows, where the Verification Manual decks were written).
/// Empty when there is none.
std::string file_in(const std::filesystem::path& directory, const std::string& name) {
  namespace fs = std::filesystem;
  std::error_code ec;
  const fs::path exact = directory / name;
  if (fs::is_regular_file(exact, ec)) return exact.string();
  const fs::path wanted(name);
  const fs::path parent = (directory / wanted).parent_path();
  const std::string leaf = to_upper(wanted.filename().string());
  for (fs::directory_iterator it(parent, ec), end; !ec && it != end; it.increment(ec))
    if (it->is_regular_file(ec) && to_upper(it->path().filename().string()) == leaf)
      return it->path().string();
  return {};
}

/// Where CDREAD finds Fname.Ext: MAPDL reads it from the working directory, where CDWRITE wrote
/// it (the run's directory here); impactfe also looks beside the deck, where an archive that
/// comes with a deck is. An absolute name is taken as it is.
std::string find_archive(const std::string& name, const std::string& deck) {
  namespace fs = std::filesystem;
  if (fs::path(name).is_absolute()) return file_in(fs::path("/"), name.substr(1));
  if (std::string found = file_in(fs::current_path(), name); !found.empty()) return found;
  const fs::path beside = fs::path(deck).parent_path();
  return file_in(beside.empty() ? fs::path(".") : beside, name);
}

// CDREAD,Option,Fname,Ext: reads a CDB archive (CDWRITE,DB) into the database, as the commands
// it holds; the processor the deck was in is kept. _CDRDOFF is 0 (no solid model was read
// first, so the archive's NUMOFF branch runs, as in MAPDL; DeckReader::run_file).
void cmd_cdread(DeckReader& r, const Command& c) {
  const std::string option = r.label(c, 1);
  if (!option.empty() && option != "DB" && option != "ALL")
    r.fail(c, fmt::format("Option '{}': DB (or ALL without an IGES file) is supported; SOLID and "
                          "COMB read solid-model data this reader does not take",
                          option));
  if (!c.blank(5) || !c.blank(6)) r.fail(c, "an IGES file (Fnamei, Exti) is not read here");
  std::string name = r.text_field(c, 2), ext = r.text_field(c, 3);
  if (name.empty()) name = r.model.jobname;
  if (ext.empty()) ext = "cdb";
  const std::string path = find_archive(name + "." + ext, c.where.file);
  if (path.empty())
    r.fail(c, fmt::format("the archive '{}.{}' does not exist in the run's directory or beside "
                          "the deck (names compared without regard to case)",
                          name, ext));
  const unsigned processor = r.processor;
  r.run_file(path, c.where);
  r.processor = processor;
  if (r.modeling.archive_terms_left > 0)
    r.fail(c, fmt::format("the archive '{}' ends {} term(s) short of constraint equation {} "
                          "(CE,R5.0,DEFI gives more terms than its CE,R5.0,NODE records)",
                          path, r.modeling.archive_terms_left, r.modeling.archive_equation));
}

// CDWRITE,Option,Fname,Ext: the model as a CDB archive (cdb_writer.h), Fname.Ext (default
// Jobname.cdb) in the run's directory.
void cmd_cdwrite(DeckReader& r, const Command& c) {
  const std::string option = r.label(c, 1);
  if (!option.empty() && option != "DB" && option != "ALL")
    r.fail(c, fmt::format("Option '{}': DB (or ALL for a model without a solid model)", option));
  if (option != "DB" && !r.model.solid.empty())
    r.fail(c,
           "ALL writes the solid model as IGES, which is not done here: CDWRITE,DB writes the "
           "mesh, materials, sections, components and loads");
  std::string name = r.text_field(c, 2), ext = r.text_field(c, 3);
  if (name.empty()) name = r.model.jobname;
  if (ext.empty()) ext = "cdb";
  const std::string path = name + "." + ext;
  std::ostringstream text;
  try {
    write_cdb(r.model, text);
  } catch (const std::invalid_argument& e) {
    r.fail(c, e.what());
  }
  std::ofstream out(path, std::ios::binary);
  out << text.str();
  out.close();
  if (!out) r.fail(c, fmt::format("cannot write '{}'", path));
  Log::info("{}:{}: CDWRITE: wrote {} ({} nodes, {} elements)", c.where.file, c.where.line, path,
            r.model.nodes.size(), r.model.elements.size());
}

// ---- settings every archive states (CDWRITE writes the solution options too) ---------------

// Settings every CDB archive states, at MAPDL's defaults, for features impactfe does not have:
// the default is what impactfe does, anything else is refused.

void cmd_irlf(DeckReader& r, const Command& c) {
  // IRLF,KEY: 0 no inertia relief (impactfe's only form); 1 and -1 are refused.
  if (const int key = r.integer(c, 1, 0); key != 0)
    r.fail(c, fmt::format("KEY {}: inertia relief is not implemented (0 only)", key));
}

void cmd_kuse(DeckReader& r, const Command& c) {
  // KUSE,KEY: 0 lets the program decide when to factor the matrix again, which impactfe does;
  // forcing reuse (1) or a new factorisation (-1) is refused.
  if (const int key = r.integer(c, 1, 0); key != 0)
    r.fail(c, fmt::format("KEY {}: only 0 (the program decides when to factor again)", key));
}

void cmd_pstres(DeckReader& r, const Command& c) {
  // PSTRES,Key: OFF (the default) computes no prestress effects; ON is refused.
  if (r.on_off(c, 1, false))
    r.fail(c,
           "ON: prestress effects (the stress stiffness of an earlier static solution in a "
           "modal or harmonic analysis) are not carried over here");
}

void cmd_crplim(DeckReader& r, const Command& c) {
  // CRPLIM,CRCR,Option: the creep-ratio limit of automatic time stepping. The defaults are
  // accepted (implicit creep, Option 1: 0, no limit, as impactfe; explicit creep, Option 0: 0.1,
  // for a creep integration impactfe does not have); any other limit is refused.
  const std::string option = r.label(c, 2);
  const bool implicit = option == "1" || option == "ON";
  if (!implicit && !option.empty() && option != "0" && option != "OFF")
    r.fail(c, fmt::format("Option '{}': 1 (implicit) or 0 (explicit)", c.text(2)));
  const double crcr = r.real(c, 1, implicit ? 0.0 : 0.1);
  if (implicit ? crcr != 0.0 : crcr != 0.1)
    r.fail(c, fmt::format("CRCR {} for {} creep: creep-ratio time-step control is not "
                          "implemented (only MAPDL's default, {})",
                          crcr, implicit ? "implicit" : "explicit", implicit ? "0" : "0.1"));
}

void cmd_ncnv(DeckReader& r, const Command& c) {
  // NCNV,KSTOP,DLIM,ITLIM,ETLIM,CPLIM: KSTOP 1 (the default) stops the run when a solution does
  // not converge, as impactfe does; the limits 0 (none). Anything else is refused.
  if (const int kstop = r.integer(c, 1, 1); kstop != 1)
    r.fail(c, fmt::format("KSTOP {}: only 1 (stop when the solution does not converge)", kstop));
  for (int f = 2; f <= 5; ++f)
    if (r.real(c, f, 0.0) != 0.0)
      r.fail(c, fmt::format("field {}: termination limits are not implemented (0 only)", f));
}

void cmd_eqslv(DeckReader& r, const Command& c) {
  // EQSLV,Lab,TOLER,MULT,--,KeepFile (MAPDL Command Reference, EQSLV). impactfe solves every
  // linear system with its sparse direct factorisation (linalg/): SPARSE is that solver; the
  // iterative solvers converge to the solution of the same equations, which the direct solve
  // gives to round-off, so their TOLER is met; MULT (their iteration-limit multiplier) and
  // KeepFile (MAPDL's scratch files) concern how MAPDL gets there. A label that is not an
  // equation solver is refused.
  const std::string lab = r.label(c, 1);
  static const std::set<std::string> kDirect = {"", "SPARSE", "SPAR", "FRONT", "DSPARSE"};
  static const std::set<std::string> kIterative = {"PCG", "JCG", "ICCG", "QMR", "JCCG", "PPCG"};
  if (!kDirect.count(lab) && !kIterative.count(lab))
    r.fail(c, fmt::format("Lab '{}' is not an equation solver (SPARSE, PCG, JCG, ICCG, QMR)", lab));
  const double toler = r.real(c, 2, 1e-8);
  if (!(toler > 0.0) || toler >= 1.0)
    r.fail(c, fmt::format("TOLER {} must lie between 0 and 1", toler));
  if (!c.blank(4)) r.fail(c, fmt::format("field 4 '{}' is not an EQSLV field", c.text(4)));
  const std::string keep = r.label(c, 5);
  if (!keep.empty() && keep != "KEEP" && keep != "DELE" && keep != "0" && keep != "1")
    r.fail(c, fmt::format("KeepFile '{}': KEEP or DELE", c.text(5)));
  // Workbench input files write `eqsl,sparse,,,,,1`: a sixth field that the command reference
  // does not describe; its 1 is accepted (it does not choose the solver), anything else refused.
  if (!c.blank(6) && r.real(c, 6, 0.0) != 1.0)
    r.fail(c, fmt::format("field 6 '{}' is not an EQSLV field (Workbench's 1 is accepted)",
                          c.text(6)));
  for (int f = 7; f <= c.n_fields(); ++f)
    if (!c.blank(f)) r.fail(c, fmt::format("field {} '{}' is not an EQSLV field", f, c.text(f)));
  if (kIterative.count(lab))
    Log::info(
        "{}:{}: EQSLV,{}: the equations are solved by the sparse direct factorisation, "
        "whose solution meets TOLER = {:g}",
        c.where.file, c.where.line, lab, toler);
}

}  // namespace

void register_cdb_commands(std::vector<CommandSpec>& t) {
  t.push_back({"CDWRITE", cmd_cdwrite, kPrep7 | kSolu});
  // Valid at the Begin level too: the archive's own /PREP7 line starts the preprocessor
  // (vm169 reads its archive before any /PREP7).
  t.push_back({"CDREAD", cmd_cdread, kBegin | kPrep7});
  t.push_back({"NUMOFF", cmd_numoff, kPrep7});
  t.push_back({"NBLOCK", cmd_nblock, kPrep7});
  t.push_back({"EBLOCK", cmd_eblock, kPrep7});
  t.push_back({"CMBLOCK", cmd_cmblock, kPrep7 | kSolu | kPost});
  t.push_back({"RLBLOCK", cmd_rlblock, kPrep7});
  t.push_back({"EQSLV", cmd_eqslv, kPrepSolu});
  t.push_back({"IRLF", cmd_irlf, kPrepSolu});
  t.push_back({"KUSE", cmd_kuse, kPrepSolu});
  t.push_back({"PSTRES", cmd_pstres, kPrepSolu});
  t.push_back({"CRPLIM", cmd_crplim, kPrepSolu});
  t.push_back({"NCNV", cmd_ncnv, kPrepSolu});
}

}  // namespace impactfe::deck
