#pragma once
/// Runs the analyses and expansion passes of a parsed job in order, writing one results file.
#include <string>

#include "analysis/run_statistics.h"
#include "analysis/structure.h"
#include "core/model.h"
#include "results/results_file.h"

namespace impactfe {

/// The model whose nodes and elements the job's results file describes: the deck's model, or —
/// for a superelement expansion pass (EXPASS + SEEXP), which must then be the job's only
/// solution, as it is a job of its own in MAPDL — the generation model stored in the
/// superelement file. InputError when the files are missing or the job mixes passes.
Model results_model(const Job& job);

/// Runs every Job::Step. Throws InputError / ModelError / NotImplementedError (exit 1) and
/// SolutionError (exit 2); the results written before the failure stay in the file, and the
/// failing analysis is marked with the error text.
void run_job(const Job& job, const std::string& jobname, const RunSettings& settings,
             ResultsWriter& writer, RunStatistics& stats);

}  // namespace impactfe
