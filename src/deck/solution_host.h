#pragma once
/// What the deck reader asks of the program that runs it. MAPDL executes a deck command by
/// command: a SOLVE solves when it is read, so *GET, POST1 and POST26 after it see its results.
/// The deck layer stays a builder: it hands each solution request to a host (the job session of
/// the analysis layer, which the layer rule keeps out of reach of the deck code) and reads the
/// results back from the results file.
#include <cstddef>
#include <string>

#include "core/model.h"

namespace impactfe {

class SolutionHost {
 public:
  virtual ~SolutionHost() = default;
  /// job.steps[step] was created, or grew by a load step (a SOLVE): solve what is new. Steps
  /// before `step` are complete. Throws the solver's errors (InputError, ModelError,
  /// SolutionError, ...), which end the deck.
  virtual void solve(const Job& job, std::size_t step) = 0;
  /// job.steps[step], just created and not solved yet, is a new analysis begun after FINISH
  /// ended an earlier one (MAPDL: leaving /SOLU ends the analysis; without ANTYPE,,REST the next
  /// SOLVE starts again at load step 1 on the model as it is then). Its results replace those
  /// the deck reads (the job session keeps the earlier file under another name).
  virtual void begin_new_analysis(const Job& job, std::size_t step) = 0;
  /// Results are about to be read (*GET of results, POST1, POST26): finish what is pending (an
  /// analysis that runs only as a whole, such as a reduced transient) and return the results
  /// file ("" when nothing was solved and no results file was given).
  virtual std::string results_for_reading(const Job& job) = 0;
  /// The deck ended: close the open analysis.
  virtual void finish(const Job& job) = 0;
  /// /CLEAR: the job ends here (the open analysis is closed, the results file complete); the next
  /// solution starts a new job and a new results file named after the jobname then current.
  virtual void clear(const Job& job) = 0;
};

}  // namespace impactfe
