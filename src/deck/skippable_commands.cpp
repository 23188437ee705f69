// The commands --skip-unknown may skip: MAPDL commands this program does not carry out whose only
// effect is on pictures, picture files, printed listings or the GUI (MAPDL Command Reference,
// "Graphics", "Display", "Listing" and GUI commands). Anything else unknown stops the run even
// with --skip-unknown: skipping TREF, BFUNIF or CP, say, silently changes the answer.
#include <algorithm>
#include <string>
#include <string_view>
#include <vector>

#include "deck/deck_context.h"

namespace impactfe::deck {

namespace {

// Names as MAPDL spells them in full. A command of this list that the program learns to carry
// out moves to the command table (a unit test keeps the two lists apart).
constexpr std::string_view kNoEffectOnResults[] = {
    // GUI macros and settings
    "JPGPRF", "KEYW", "/UI", "/MSTART", "/MENU", "/PMETH",
    // picture files and devices
    "JPEG", "/SEG", "/IMAGE", "/PSCR", "/DEVDISP", "/DV3D", "/GSAVE", "/GRESUME", "/GCMD",
    "/GFORMAT", "/ANFILE", "PNGR", "TIFF", "PSCR", "HPGL", "/CMAP",
    // views, scaling, labels and styles of pictures
    "/VSCALE", "/SSCALE", "/RATIO", "/NUMBER", "/GRTYP", "/GMARKER", "/LSYMBOL", "/EFACET", "/CVAL",
    "/CLABEL", "/CPLANE", "/EXPAND", "/SHADE", "/SHRINK", "/LIGHT", "/NORMAL", "/TRLCY", "/FACET",
    "/ANUM", "/CTYPE", "/ICLWID", "/ICSCALE", "/PBF", "/PICE", "/PSPEC", "/LSPEC", "/TSPEC",
    "/TXTRE", "/HBC", "/GMATRIX", "/MREP", "/VCONE", "/XFRM", "/ANNOT", "/TLABEL", "/LARC",
    "/POLYGON", "/PMORE", "/PCIRCLE", "/STITLE", "/UDOC", "/GTYPE", "/RESET",
    // plots
    "APLOT", "KPLOT", "LPLOT", "VPLOT", "SECPLOT", "*VPLOT", "PLLS", "PLVECT", "PLCAMP", "PLORB",
    "PLTRAC", "PLGEOM", "PLCINT", "PLCRACK", "PLZZ", "PLMC", "PLTIME", "PLTLINE", "PLOT", "REPLOT",
    "TBPLOT", "PLHFFAR", "PLFAR", "CMPLOT",
    // printed listings
    "PRCAMP", "PRORB", "PRERR", "PRCINT", "PRENERGY", "PRJSOL", "PRITER", "PRNLD", "PRRFOR",
    "IRLIST", "SLIST", "TBLIST", "SECLIST", "CPLIST", "BFLIST", "BFELIST", "SFLIST", "SFELIST",
    "DKLIST", "FKLIST", "STAT"};

/// Leading '/' or '*' plus up to four characters: the part of a name MAPDL reads.
std::string_view significant(std::string_view name) {
  const std::size_t lead = (!name.empty() && (name[0] == '/' || name[0] == '*')) ? 1 : 0;
  return name.substr(0, std::min(name.size(), lead + 4));
}

}  // namespace

bool cannot_change_results(const std::string& name) {
  for (std::string_view listed : kNoEffectOnResults) {
    if (name == listed) return true;
    // An abbreviation of at least four characters, or a longer spelling with the same four
    // significant characters (the command lookup's rules).
    if (name.size() >= 4 && name.size() < listed.size() && listed.substr(0, name.size()) == name)
      return true;
    if (name.size() > significant(name).size() && significant(name) == significant(listed))
      return true;
  }
  return false;
}

const std::vector<std::string_view>& commands_without_effect_on_results() {
  static const std::vector<std::string_view> all(std::begin(kNoEffectOnResults),
                                                 std::end(kNoEffectOnResults));
  return all;
}

}  // namespace impactfe::deck
