#pragma once
/// Runs the analyses and expansion passes of a parsed job in order, writing one results file.
#include <string>

#include "analysis/run_statistics.h"
#include "analysis/structure.h"
#include "core/model.h"
#include "results/results_file.h"

namespace impactfe {

/// Runs every Job::Step. Throws InputError / ModelError / NotImplementedError (exit 1) and
/// SolutionError (exit 2); the results written before the failure stay in the file, and the
/// failing analysis is marked with the error text.
void run_job(const Job& job, const std::string& jobname, const RunSettings& settings,
             ResultsWriter& writer, RunStatistics& stats);

}  // namespace impactfe
