// Commands a Workbench input file (ds.dat) writes around its SOLVE that concern MAPDL's own
// files and diagnostics rather than the model: DMPOPTION, CNTR, NLDIAG, CEWRITE, XMLO and /XML.
// Each is carried out as far as impactfe has what it asks for, or refused where it has not.
#include <fmt/format.h>

#include <algorithm>
#include <fstream>
#include <set>
#include <string>

#include "core/log.h"
#include "deck/deck_context.h"
#include "results/svg_plot.h"  // xml_escape

namespace impactfe::deck {

namespace {

/// True when the model has contact elements (CONTA17x, CONTAC12/52): contact diagnostics then
/// have something to report, which impactfe does not write (CNTR, NLDIAG,CONT).
bool has_contact_elements(const DeckReader& r) {
  return std::any_of(r.model.element_types.begin(), r.model.element_types.end(),
                     [](const auto& et) { return et.second.ansys_name.rfind("CONTA", 0) == 0; });
}

/// DMPOPTION,FileType,Combine: whether Distributed ANSYS combines its per-process files. impactfe
/// writes none: rank 0 writes the one results file of the run, so there is nothing to combine
/// (or to keep apart) whatever Combine says.
void cmd_dmpoption(DeckReader& r, const Command& c) {
  static const std::set<std::string> kFiles = {"RST", "RTH", "RMG",  "RSTP", "EMAT", "ESAV", "MODE",
                                               "MLV", "IST", "FULL", "RFRQ", "RDSP", "RNNN"};
  const std::string file = r.label(c, 1);
  if (!kFiles.count(file))
    r.fail(c, fmt::format("FileType '{}' is not a solution file (RST, RTH, RMG, RSTP, EMAT, ESAV, "
                          "MODE, MLV, IST, FULL, RFRQ, RDSP, RNNN)",
                          c.text(1)));
  const std::string combine = r.label(c, 2);
  if (!combine.empty() && combine != "YES" && combine != "NO" && combine != "1" && combine != "0")
    r.fail(c, fmt::format("Combine '{}': YES or NO", c.text(2)));
  for (int f = 3; f <= c.n_fields(); ++f)
    if (!c.blank(f)) r.fail(c, fmt::format("field {} '{}' is not a DMPOPTION field", f, c.text(f)));
  Log::info(
      "{}:{}: DMPOPTION,{}: impactfe writes no per-process files (rank 0 writes the results "
      "file): nothing to combine",
      c.where.file, c.where.line, file);
}

/// CNTR,Option,Key: where contact-pair output goes (OUT: Jobname.CNM or the output) and, as
/// Workbench writes it (PRINT,1), a printout of each pair's initial state. impactfe writes its
/// contact results to the results file; a model without contact elements has no pair to print,
/// and the command is then carried out. With contact elements a redirected or printed pair
/// report would be missing: refused.
void cmd_cntr(DeckReader& r, const Command& c) {
  const std::string option = r.label(c, 1);
  const std::string key = r.label(c, 2);
  if (option != "OUT" && option != "PRINT")
    r.fail(c, fmt::format("Option '{}': OUT or PRINT", c.text(1)));
  const bool off = key.empty() || key == "NO" || key == "0";
  if (!off && key != "YES" && key != "1")
    r.fail(c, fmt::format("Key '{}': YES or NO (1 or 0)", c.text(2)));
  if (!off && has_contact_elements(r))
    r.fail(c, fmt::format("CNTR,{},{}: contact pair reports are not written (contact results are "
                          "in the results file: post, PRESOL of the contact elements)",
                          option, key));
}

/// NLDIAG,Label,Key,MAXFILE: nonlinear diagnostics files. CONT (contact information per
/// iteration, substep or load step, Jobname.cnd) is carried out for a model without contact
/// elements (there is none to write); the residual (NRRE) and element-flag (EFLG) files are not
/// written. Key OFF (or NO, 0) is always accepted.
void cmd_nldiag(DeckReader& r, const Command& c) {
  const std::string label = r.label(c, 1);
  const std::string key = r.label(c, 2);
  static const std::set<std::string> kKeys = {"",  "ON",   "OFF",  "YES",  "NO",   "0",
                                              "1", "ITER", "SBST", "LSTP", "STAT", "DEL"};
  if (label != "CONT" && label != "NRRE" && label != "EFLG")
    r.fail(c, fmt::format("Label '{}': CONT, NRRE or EFLG", c.text(1)));
  if (!kKeys.count(key)) r.fail(c, fmt::format("Key '{}' is not an NLDIAG key", c.text(2)));
  if (key == "OFF" || key == "NO" || key == "0" || key == "STAT" || key == "DEL") return;
  if (label != "CONT")
    r.fail(c, fmt::format("NLDIAG,{}: the nonlinear diagnostics files (Jobname.nr/.nd) are not "
                          "written; the run summary and the log give each iteration's residual",
                          label));
  if (has_contact_elements(r))
    r.fail(c,
           "NLDIAG,CONT: the contact diagnostics file (Jobname.cnd) is not written; contact "
           "status changes per substep are in the log");
}

/// CEWRITE,Fname,Ext,--,DOFCODE,DOFLIST: writes the constraint equations as CE commands (blank
/// DOFCODE) or the internal ones of MPC-based contact (INTE), which impactfe never generates
/// (its contact is penalty or augmented Lagrange): the file then holds a header only.
void cmd_cewrite(DeckReader& r, const Command& c) {
  std::string name = r.text_field(c, 1);
  std::string ext = r.text_field(c, 2);
  if (name.empty()) name = r.model.jobname;
  if (ext.empty()) ext = "ce";
  const std::string code = r.label(c, 4);
  if (!code.empty() && code != "INTE")
    r.fail(c, fmt::format("DOFCODE '{}': blank (the CE equations) or INTE", c.text(4)));
  if (!c.blank(5)) r.fail(c, "DOFLIST is not supported (every DOF is written)");
  const std::string path = name + "." + ext;
  std::ofstream out(path);
  if (!out) r.fail(c, fmt::format("cannot open '{}' for writing", path));
  out << "! constraint equations written by impactfe (CEWRITE"
      << (code.empty() ? "" : ", internal: none, no MPC-based contact") << ")\n";
  if (code.empty())
    for (const auto& [id, ce] : r.model.constraint_equations)
      for (std::size_t k = 0; k < ce.terms.size(); k += 3) {
        std::string line = fmt::format("CE,{},{:.15g}", id, ce.constant);
        for (std::size_t t = k; t < std::min(k + 3, ce.terms.size()); ++t)
          line += fmt::format(",{},{},{:.15g}", ce.terms[t].dof.node, dof_name(ce.terms[t].dof.dof),
                              ce.terms[t].coefficient);
        out << line << '\n';
      }
  if (!out) r.fail(c, fmt::format("writing '{}' failed", path));
}

/// XMLO,Key,Value: options of /XML. ENCODING (ISO-8859-1 or UTF-8, written in the XML
/// declaration) and PARM (parameters are what /XML writes; the only content impactfe offers).
void cmd_xmlo(DeckReader& r, const Command& c) {
  const std::string key = r.label(c, 1);
  if (key == "PARM") return;
  if (key != "ENCODING") r.fail(c, fmt::format("Key '{}': ENCODING or PARM", c.text(1)));
  const std::string value = r.label(c, 2);
  if (value != "ISO-8859-1" && value != "UTF-8")
    r.fail(c, fmt::format("ENCODING '{}': ISO-8859-1 or UTF-8", c.text(2)));
  r.scripting.xml_encoding = value;
}

/// /XML,Fname,Ext: writes the global scalar parameters (numbers and character strings) to
/// Fname.Ext as <parameter name= type=> elements (impactfe's own layout, docs/deck_reader.md);
/// Workbench reads its run statistics back this way.
void cmd_xml(DeckReader& r, const Command& c) {
  std::string name = r.text_field(c, 1);
  std::string ext = r.text_field(c, 2);
  if (name.empty()) name = r.model.jobname;
  if (ext.empty()) ext = "xml";
  const std::string path = name + "." + ext;
  std::ofstream out(path);
  if (!out) r.fail(c, fmt::format("cannot open '{}' for writing", path));
  out << "<?xml version=\"1.0\" encoding=\"" << r.scripting.xml_encoding << "\"?>\n<parameters>\n";
  for (const auto& [pname, p] : r.params.all()) {
    if (p.type == ParamType::Number)
      out << fmt::format("  <parameter name=\"{}\" type=\"number\">{:.15g}</parameter>\n",
                         xml_escape(pname), p.number);
    else if (p.type == ParamType::Text)
      out << fmt::format("  <parameter name=\"{}\" type=\"string\">{}</parameter>\n",
                         xml_escape(pname), xml_escape(p.text));
  }
  out << "</parameters>\n";
  if (!out) r.fail(c, fmt::format("writing '{}' failed", path));
}

}  // namespace

void register_workbench_commands(std::vector<CommandSpec>& t) {
  t.push_back({"DMPOPTION", cmd_dmpoption, kPrepSolu});
  t.push_back({"CNTR", cmd_cntr, kPrepSolu});
  t.push_back({"NLDIAG", cmd_nldiag, kPrepSolu});
  t.push_back({"CEWRITE", cmd_cewrite, kAnywhere});
  t.push_back({"XMLO", cmd_xmlo, kAnywhere});
  t.push_back({"/XML", cmd_xml, kAnywhere});
}

}  // namespace impactfe::deck
