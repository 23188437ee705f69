#pragma once
/// Reads an APDL deck (ANSYS 4.2 "4x" dialect or modern Mechanical APDL) into a Job: the model
/// plus the ordered list of analyses, expansion passes and post-processing commands.
/// The deck layer only builds; it never solves.
#include <cstddef>
#include <optional>
#include <ostream>
#include <string>

#include "core/model.h"

namespace impactfe {

class SolutionHost;

struct DeckOptions {
  std::optional<Dialect> dialect;  // nullopt = auto-detect (spec §2.3)
  bool skip_unknown = false;       // unknown commands become listed warnings
  std::string jobname;             // default: the deck's file stem (or /FILNAME)
  /// Results file of a post-only deck (`impactfe run --results FILE`); see post_support.h for
  /// how a deck that solves nothing finds its results otherwise.
  std::string results_file;
  /// Solves each request as the deck reaches it (null: requests are only collected).
  SolutionHost* host = nullptr;
  /// Most nodes and most elements the deck may define: N, E and the generation commands that
  /// would go beyond are refused up front (never attempted until memory runs out).
  std::size_t max_nodes = 10'000'000;
  std::size_t max_elements = 10'000'000;
  /// Most interpreted work: commands executed plus loop trips, *REPEAT repetitions and *DO
  /// block passes (each at most 10⁷ per loop); beyond, the deck fails as a runaway loop.
  long long max_commands = 50'000'000;
  /// Where the deck's printed output goes until /OUT redirects it (*VWRITE, *MSG, *STATUS,
  /// /COM, PRNSOL, ...). Null: to the log; `impactfe run` passes std::cout.
  std::ostream* output = nullptr;
  /// MPI ranks the run's solutions use (1 without MPI): *GET,Par,ACTIVE,,SOLU,DLBR.
  int processes = 1;
};

/// Parses `path` (following /INPUT files). Throws InputError "FILE:LINE: COMMAND: what".
Job read_deck(const std::string& path, const DeckOptions& options = {});

/// Same, from text (for tests); `virtual_path` names it in messages and resolves /INPUT.
Job read_deck_text(const std::string& text, const std::string& virtual_path,
                   const DeckOptions& options = {});

}  // namespace impactfe
