#pragma once
/// Deck-reading state of the APDL interpreter beyond the parameters: the 4x *SET increments, the
/// 4x *BEGIN blocks, the files *CREATE makes in memory, the *CFOPEN command file and the vector
/// settings of the next *V / *M command. Written by the scripting handlers (parameters, arrays,
/// macros, output).
#include <fstream>
#include <map>
#include <optional>
#include <string>
#include <vector>

#include "deck/lexer.h"

namespace impactfe::deck {

/// A file made by *CREATE (kept in memory, APDL_SCRIPTING §A.13): its lines as lexed commands
/// (with their deck locations, so errors point into the deck) and as text (*LIST).
struct MacroFile {
  std::vector<RawCommand> commands;
  std::vector<std::string> lines;
};

/// Vector-operation settings (*VFACT, *VMASK, *VLEN, *VCUM, *VABS, *VCOL; APDL_MODELING §10.2):
/// they apply to the next *V / *M command and are then reset.
struct VectorSettings {
  double factor_result = 1.0, factor1 = 1.0, factor2 = 1.0, factor3 = 1.0;  // *VFACT
  std::string mask;                                                   // *VMASK,Par(i) ("" = none)
  std::optional<int> n_rows;                                          // *VLEN NROW
  int row_increment = 1;                                              // *VLEN NINC
  bool cumulate = false;                                              // *VCUM,1
  bool abs_result = false, abs1 = false, abs2 = false, abs3 = false;  // *VABS
  std::optional<int> n_cols1, n_cols2;                                // *VCOL
};

/// The *CFOPEN command file: *CFWRITE lines and *VWRITE output go there while it is open.
struct CommandFileState {
  std::ofstream stream;
  std::string path;
};
struct ScriptingState {
  std::map<std::string, double> increments;               // 4x *SET,Par,VALUE,INC
  std::map<std::string, std::vector<RawCommand>> macros;  // 4x *BEGIN blocks
  std::map<std::string, MacroFile> files;                 // *CREATE files: "NAME.EXT" / "NAME"
  CommandFileState command_file;                          // *CFOPEN
  VectorSettings vector_settings;                         // *VFACT *VMASK *VLEN *VCUM *VABS *VCOL
  std::string xml_encoding = "ISO-8859-1";                // XMLO,ENCODING (for /XML)
};

}  // namespace impactfe::deck
