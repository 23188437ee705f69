#include "analysis/job_session.h"

#include <fmt/format.h>

#include <algorithm>
#include <filesystem>
#include <map>

#include "analysis/analyses.h"
#include "analysis/direct_solution.h"
#include "analysis/progress.h"
#include "analysis/superelement_expansion.h"
#include "core/interruption.h"
#include "core/job_lock.h"
#include "core/log.h"
#include "elements/model_memory.h"
#include "explicit/explicit_run.h"
#include "explicit/explicit_system.h"
#include "results/output_selection.h"

namespace impactfe {

namespace {

bool is_superelement_expansion(const Job::Step& step) {
  return step.expansion && step.expansion->superelement;
}

/// Static and full transient analyses advance load step by load step.
bool solves_incrementally(const AnalysisOptions& o) {
  return o.type == AnalysisType::Static ||
         (o.type == AnalysisType::Transient && o.method == TransientMethod::Full);
}

/// A static or full transient analysis whose elements are all explicit ones (16x) is an
/// explicit dynamics run, as in MAPDL's ANSYS LS-DYNA (docs/explicit_dynamics.md); explicit
/// elements mixed with implicit ones are refused.
bool runs_explicit_dynamics(const Job::Step& step) {
  if (!step.analysis || !solves_incrementally(step.analysis->options)) return false;
  const Model& model = *step.model_snapshot;
  if (!has_explicit_elements(model)) return false;
  std::string why;
  if (runs_explicit(model, &why)) return true;
  throw InputError(step.analysis->where,
                   fmt::format("explicit (16x) elements are mixed with implicit ones: {}; an "
                               "explicit analysis takes explicit elements only",
                               why));
}

/// The explicit run (src/explicit) has no constraint equations: CE and CERIG are refused there
/// rather than ignored.
void refuse_constraint_equations(const Model& model) {
  if (!model.constraint_equations.empty())
    throw NotImplementedError(model.constraint_equations.begin()->second.where,
                              "constraint equations (CE) in explicit dynamics are not implemented");
  if (!model.rigid_regions.empty())
    throw NotImplementedError(model.rigid_regions.front().where,
                              "rigid regions (CERIG) in explicit dynamics are not implemented");
}

/// EDMP,RIGID acts in explicit dynamics only: an implicit analysis of a model that has rigid
/// materials refuses them rather than solving them as deformable.
void refuse_rigid_materials(const Model& model) {
  for (const auto& [mat, rigid] : model.explicit_dynamics.rigid_materials)
    for (const auto& [id, record] : model.elements)
      if (record.mat == mat)
        throw InputError(rigid.where,
                         fmt::format("material {} is rigid (EDMP,RIGID), which explicit dynamics "
                                     "carries out; element {} of it is in an implicit analysis",
                                     mat, id));
}

const SourceLocation& location_of(const Job::Step& step) {
  return step.analysis ? step.analysis->where : step.expansion->where;
}

/// A superelement's nodes (its master nodes) come from its file, so the model section of the
/// results file lacks them until the element is built: record them then, for the exports.
void record_file_defined_nodes(const Structure& structure, ResultsWriter& writer) {
  std::map<int, std::vector<int>> lists;
  for (const auto& e : structure.elements()) {
    const auto record = structure.model().elements.find(e->id());
    if (record == structure.model().elements.end() || !record->second.nodes.empty()) continue;
    std::vector<int>& nodes = lists[e->id()];
    for (const auto& key : e->dofs())
      if (std::find(nodes.begin(), nodes.end(), key.node) == nodes.end()) nodes.push_back(key.node);
  }
  if (!lists.empty()) writer.set_element_nodes(lists);
}

/// Whether a pass may read superelement files that another MPI rank generated: anything but a
/// generation pass whose model has no superelement itself (the generations run concurrently,
/// one per rank, until such a pass, docs/scaling.md).
bool needs_generated_superelements(const Job& job, const Job::Step& step) {
  if (!step.analysis || step.analysis->options.type != AnalysisType::Substructure) return true;
  return std::any_of(job.model.elements.begin(), job.model.elements.end(),
                     [](const auto& e) { return !e.second.superelement_file.empty(); });
}

}  // namespace

Model results_model(const Job& job, std::size_t step) {
  if (step < job.steps.size() && is_superelement_expansion(job.steps[step])) {
    const SuperelementExpansionSource& source = *job.steps[step].expansion->superelement;
    const SuperelementData data = read_superelement(superelement_file_of(source), source.where);
    bool lumped = false, sstif = false;
    Model model = deserialize_generation_model(data.model_text, lumped, sstif);
    model.title = data.title;
    model.jobname = job.model.jobname;
    return model;
  }
  return job.model;
}

JobSession::JobSession(std::string jobname, const RunSettings& settings, RunStatistics& stats)
    : jobname_(std::move(jobname)), settings_(settings), stats_(stats) {}

JobSession::JobSession(ResultsWriter& writer, std::string jobname, const RunSettings& settings,
                       RunStatistics& stats)
    : jobname_(std::move(jobname)), settings_(settings), stats_(stats), writer_(&writer) {}

JobSession::~JobSession() = default;

std::string JobSession::results_path() const {
  if (writer_) return writer_->path();
  return closed_files_.empty() ? std::string() : closed_files_.back();
}

ResultsWriter& JobSession::writer_for(const Job& job, std::size_t step) {
  const bool expansion = is_superelement_expansion(job.steps[step]);
  // The step being opened is the only one of this job (since the start or the last /CLEAR).
  const bool first = stats_.analyses.size() == job_first_analysis_ + 1;
  if ((expansion && !first) || (!expansion && superelement_expansion_job_))
    throw InputError(location_of(job.steps[step]),
                     "a superelement expansion pass (EXPASS + SEEXP) must be the only solution "
                     "of its job (MAPDL runs it as a job of its own: /CLEAR, /FILNAME,Sename)");
  superelement_expansion_job_ = expansion;
  if (!writer_) {
    if (!job.model.jobname.empty()) jobname_ = job.model.jobname;  // /FILNAME before the solution
    for (const auto& old : closed_files_)
      if (old == jobname_ + ".h5")
        Log::warn(
            "{}: the results file of the job before /CLEAR is replaced (give the new job "
            "its own name with /FILNAME)",
            old);
    // A run continued from a restart point (ANTYPE,,RESTART) adds its analysis to the results
    // file of the run it continues.
    const std::string path = jobname_ + ".h5";
    const Job::Step& s = job.steps.at(step);
    // No file of the job is touched before the job is ours: a second run of the same job in the
    // same directory would otherwise truncate the results file the first is writing.
    try {
      // A new analysis's file (supersede_results_file) is made under the job's lock already held.
      if (!job_lock_) job_lock_ = JobLock::acquire(path);
    } catch (const JobLockedError& e) {
      throw InputError(location_of(s), e.what());
    } catch (const std::runtime_error& e) {
      throw SolutionError(location_of(s), e.what());
    }
    if (s.analysis && s.analysis->options.restart && std::filesystem::exists(path))
      owned_writer_ = std::make_unique<ResultsWriter>(path, ResultsWriter::Append{});
    else
      owned_writer_ = std::make_unique<ResultsWriter>(path, results_model(job, step));
    writer_ = owned_writer_.get();
  }
  return *writer_;
}

namespace {

/// Whether the model section of a results file written for `a` describes `b` too: the same
/// nodes (numbers, coordinates) and elements (number, type, material, real set, section, nodes).
bool same_model_section(const Model& a, const Model& b) {
  if (a.nodes.size() != b.nodes.size() || a.elements.size() != b.elements.size()) return false;
  for (auto i = a.nodes.begin(), j = b.nodes.begin(); i != a.nodes.end(); ++i, ++j)
    if (i->first != j->first || i->second.x != j->second.x) return false;
  for (auto i = a.elements.begin(), j = b.elements.begin(); i != a.elements.end(); ++i, ++j) {
    const ElementRecord& x = i->second;
    const ElementRecord& y = j->second;
    if (i->first != j->first || x.type != y.type || x.mat != y.mat || x.real != y.real ||
        x.secnum != y.secnum || x.esys != y.esys || x.nodes != y.nodes)
      return false;
  }
  return true;
}

/// A new analysis after FINISH that the results file can hold beside the earlier ones: of
/// another type than the analysis before it (a modal analysis, then a transient: nothing of the
/// two is merged) on the same model section. One of the same type would mix its load steps and
/// times with the earlier analysis's, and a changed model would not match the file's model.
bool fits_the_same_file(const Job& job, std::size_t step) {
  const Job::Step& s = job.steps[step];
  for (std::size_t k = step; k-- > 0;) {
    const Job::Step& p = job.steps[k];
    if (!p.analysis) continue;
    return p.analysis->options.type != s.analysis->options.type &&
           same_model_section(*p.model_snapshot, *s.model_snapshot);
  }
  return true;
}

}  // namespace

void JobSession::begin_new_analysis(const Job&, std::size_t step) {
  new_analysis_ = step;
}

void JobSession::supersede_results_file(const Job& job, std::size_t step) {
  const Job::Step& s = job.steps[step];
  if (new_analysis_ != step || !s.analysis) return;
  new_analysis_.reset();
  if (!writer_ || fits_the_same_file(job, step)) return;
  if (!owned_writer_)
    throw InputError(location_of(s),
                     "a new analysis after FINISH needs a results file of its own, and this run "
                     "writes into a results file it was given (solve the deck with `impactfe "
                     "run`)");
  const std::string path = owned_writer_->path();
  owned_writer_.reset();  // the earlier analyses are complete and closed
  writer_ = nullptr;
  if (!job.model.jobname.empty() && job.model.jobname + ".h5" != path) {
    // /FILNAME named another job since: the new analysis writes that job's file, this one stays.
    closed_files_.push_back(path);
    job_lock_.reset();
    return;
  }
  const std::string base = path.size() > 3 && path.compare(path.size() - 3, 3, ".h5") == 0
                               ? path.substr(0, path.size() - 3)
                               : path;
  const std::string kept = fmt::format("{}.{}.h5", base, ++superseded_files_);
  std::error_code ec;
  std::filesystem::rename(path, kept, ec);
  if (ec)
    throw SolutionError(location_of(s),
                        fmt::format("a new analysis begins, and the results of the earlier one "
                                    "could not be kept: renaming {} to {} failed: {}",
                                    path, kept, ec.message()));
  closed_files_.push_back(kept);
  Log::info(
      "{}:{}: SOLVE: a new analysis begins (FINISH ended the earlier one; ANTYPE,,REST would "
      "continue it): its results go to a new {}, the earlier analyses' results are kept in {}",
      s.analysis->where.file, s.analysis->where.line, path, kept);
}

void JobSession::solve(const Job& job, std::size_t step) {
  IMPACTFE_CHECK(step < job.steps.size(), "solution request out of range");
  const Job::Step& s = job.steps[step];
  if (open_ && *open_ != step) close_open();
  const auto start = std::chrono::steady_clock::now();
  where_ = location_of(s);
  try {
    if (!open_ && needs_generated_superelements(job, s)) share_generated_superelements();
    if (!open_) supersede_results_file(job, step);
    if (!open_) {
      // Refused before anything large is built when the model cannot fit (the symbolic
      // analysis checks the factor exactly later).
      // An explicit run keeps no matrix and no factor: the estimate (of a factorisation) is not
      // its need (its arrays are a few hundred bytes per element).
      explicit_ = runs_explicit_dynamics(s);
      if (s.analysis && !explicit_) refuse_rigid_materials(*s.model_snapshot);
      if (s.analysis && explicit_) refuse_constraint_equations(*s.model_snapshot);
      if (s.analysis && !explicit_) require_model_memory(*s.model_snapshot, "SOLVE");
      const auto& restart = s.analysis ? s.analysis->options.restart : std::nullopt;
      if (restart && !solves_incrementally(s.analysis->options))
        throw InputError(restart->where,
                         "ANTYPE,,RESTART continues a static or full transient analysis only "
                         "(reduced and mode-superposition transients solve as a whole)");
      stats_.analyses.emplace_back();
      AnalysisStatistics& current = stats_.analyses.back();
      // A solution solved increment by increment builds its structure before the results
      // file is opened: the file's writer thread starts HDF5 and creates the file while this
      // thread reads the superelement files the structure needs, and HDF5 serves one thread at
      // a time (the use pass of the thesis's helmet waited 5 ms for it, issue 11).
      const bool incremental =
          s.analysis && solves_incrementally(s.analysis->options) && !explicit_;
      if (incremental) {
        models_.push_back(s.model_snapshot);
        structure_ = std::make_unique<Structure>(*models_.back(), s.analysis->options, settings_,
                                                 &s.analysis->load_steps);
      }
      ResultsWriter& writer = writer_for(job, step);
      open_ = step;
      open_seconds_ = 0.0;
      load_steps_solved_ = 0;
      if (s.expansion) {
        // An expansion pass is complete when it is requested: it runs now and closes.
        if (s.expansion->superelement) {
          run_superelement_expansion(*s.expansion, writer, current);
        } else {
          current.description = "expansion pass";
          run_expansion_pass(*s.expansion, reduced_state_.get(), writer, settings_, current);
        }
        open_seconds_ =
            std::chrono::duration<double>(std::chrono::steady_clock::now() - start).count();
        close_open();
        return;
      }
      if (!incremental) models_.push_back(s.model_snapshot);
      open_step_.emplace();
      open_step_->analysis = *s.analysis;
      if (incremental) {
        structure_->use_table_nodes(writer.node_ids());
        record_file_defined_nodes(*structure_, writer);
        // The file's time blocks fit the points when the load steps are all known.
        direct_ = begin_direct_analysis(*structure_, writer, settings_, current,
                                        s.analysis->load_steps, s.analysis->complete && !restart);
      }
    }
    // The analysis grew by the load steps its SOLVEs appended since the last call.
    open_step_->analysis->load_steps = s.analysis->load_steps;
    if (direct_) {
      const auto& steps = open_step_->analysis->load_steps;
      while (load_steps_solved_ < steps.size()) {
        where_ = steps[load_steps_solved_].where;
        direct_->look_ahead(
            {steps.begin() + static_cast<long>(load_steps_solved_) + 1, steps.end()});
        direct_->solve_load_step(steps[load_steps_solved_++]);
      }
    }
  } catch (...) {
    open_seconds_ +=
        std::chrono::duration<double>(std::chrono::steady_clock::now() - start).count();
    fail(std::current_exception());
  }
  open_seconds_ += std::chrono::duration<double>(std::chrono::steady_clock::now() - start).count();
}

void JobSession::run_whole(const Job::Step& step, AnalysisStatistics& stats) {
  const AnalysisRequest& request = *step.analysis;
  if (explicit_) {
    stats.description = "explicit dynamics (central difference)";
    ExplicitRunOptions options{.accept_energy_error = settings_.accept_energy_error};
    if (ProgressObserver* observer = settings_.progress)
      options.progress = [observer](const ExplicitProgress& p) {
        ProgressEvent e;
        e.analysis = "explicit dynamics";
        e.time = p.time;
        e.time_end = p.load_step_end;
        e.load_step = p.load_step;
        // No substeps: the end of a load step counts as its last one (always drawn).
        e.substep = p.last_of_load_step ? 1 : 0;
        e.substeps = 1;
        e.dt = p.dt;
        e.status_changes = -1;
        e.substeps_left = 0;  // the estimate runs to the end of the last load step
        e.run_time_end = p.run_end;
        e.cycles = p.cycles;
        e.energy_error = p.energy_error;
        observer->substep_done(e);
      };
    const ExplicitRunSummary summary =
        run_explicit_analysis(*models_.back(), request, *writer_, options);
    stats.n_load_steps = static_cast<int>(request.load_steps.size());
    stats.n_substeps = static_cast<int>(summary.cycles);
    stats.n_stored = summary.stored_points;
    stats.notes.insert(stats.notes.end(), summary.notes.begin(), summary.notes.end());
    for (const auto& note : summary.notes) Log::info("{}", note);
    return;
  }
  Structure structure(*models_.back(), request.options, settings_, &request.load_steps);
  structure.use_table_nodes(writer_->node_ids());
  record_file_defined_nodes(structure, *writer_);
  switch (request.options.type) {
    case AnalysisType::Modal:
      run_modal_analysis(structure, request, *writer_, settings_, stats);
      break;
    case AnalysisType::Transient:
      // Reduced and MSUP runs store every item at every substep (time/time_axis.cpp): whatever
      // OUTRES asks for (per item, component or frequency) is written, and more.
      for (const LoadStep& ls : request.load_steps)
        if (!ls.output.uniform())
          Log::info(
              "{}:{}: OUTRES per item: a reduced or mode-superposition transient writes "
              "every item at every substep",
              ls.where.file, ls.where.line);
      if (request.options.method == TransientMethod::Reduced)
        run_reduced_transient(structure, request, *writer_, settings_, stats, reduced_state_);
      else
        run_msup_transient(structure, request, *writer_, settings_, stats, reduced_state_);
      break;
    case AnalysisType::Harmonic:
      run_harmonic_analysis(structure, request, *writer_, settings_, stats);
      break;
    case AnalysisType::Spectrum:
      run_spectrum_analysis(structure, request, *writer_, settings_, stats);
      break;
    case AnalysisType::Substructure:
      run_substructure_generation(structure, request, *writer_, settings_, stats, jobname_);
      break;
    case AnalysisType::Static:
      IMPACTFE_CHECK(false, "a static analysis is solved load step by load step");
  }
}

void JobSession::close_open() {
  if (!open_) return;
  AnalysisStatistics& current = stats_.analyses.back();
  const auto start = std::chrono::steady_clock::now();
  if (!direct_ && open_step_ && open_step_->analysis) where_ = open_step_->analysis->where;
  try {
    if (direct_)
      direct_->finish();
    else if (open_step_ && open_step_->analysis)
      run_whole(*open_step_, current);
  } catch (...) {
    open_seconds_ +=
        std::chrono::duration<double>(std::chrono::steady_clock::now() - start).count();
    fail(std::current_exception());
  }
  current.wall_seconds =
      open_seconds_ +
      std::chrono::duration<double>(std::chrono::steady_clock::now() - start).count();
  writer_->set_attribute("wall_seconds", current.wall_seconds);
  writer_->set_count("factorizations", static_cast<long long>(current.n_factorizations));
  writer_->set_count("dofs", static_cast<long long>(current.n_dofs));
  writer_->set_count("substeps", static_cast<long long>(current.n_substeps));
  writer_->set_count("iterations", static_cast<long long>(current.n_iterations));
  writer_->set_count("status_changes", static_cast<long long>(current.n_status_changes));
  if (current.n_cuts > 0)
    writer_->set_count("time_step_cuts", static_cast<long long>(current.n_cuts));
  if (current.factor_nonzeros > 0) {  // linear solver figures (docs/results_file.md)
    writer_->set_count("solves", static_cast<long long>(current.n_solves));
    writer_->set_attribute("analyze_seconds", current.analyze_seconds);
    writer_->set_attribute("factorize_seconds", current.factorize_seconds);
    writer_->set_attribute("solve_seconds", current.solve_seconds);
    writer_->set_count("matrix_nonzeros", static_cast<long long>(current.matrix_nonzeros));
    writer_->set_count("factor_nonzeros", static_cast<long long>(current.factor_nonzeros));
    writer_->set_count("factor_bytes", static_cast<long long>(current.factor_bytes));
  }
  writer_->end_analysis("complete");
  direct_.reset();
  structure_.reset();
  open_step_.reset();
  open_.reset();
}

void JobSession::fail(const std::exception_ptr& error) {
  if (!stats_.analyses.empty()) stats_.analyses.back().wall_seconds = open_seconds_;
  std::exception_ptr located;
  try {
    std::rethrow_exception(error);
  } catch (const ElementSolutionError& e) {
    // Name the element's E command too: the failure is the element's, the step is where.
    std::string defined;
    if (!models_.empty()) {
      const auto it = models_.back()->elements.find(e.element());
      if (it != models_.back()->elements.end() && it->second.where.known())
        defined = fmt::format(" (element {} is defined at {})", e.element(),
                              location_text(it->second.where));
    }
    located = std::make_exception_ptr(SolutionError(where_, e.message() + defined));
  } catch (...) {
    try {
      rethrow_at(where_);
    } catch (...) {
      located = std::current_exception();
    }
  }
  try {
    std::rethrow_exception(located);
  } catch (const RunInterrupted&) {
    try {
      if (writer_) writer_->end_analysis("interrupted");  // docs/results_file.md, status
    } catch (...) {
      // The file cannot be written any more: it keeps its last flushed state.
    }
  } catch (const std::exception& e) {
    try {
      if (writer_) writer_->end_analysis(std::string("failed: ") + e.what());
    } catch (...) {
      // No analysis group was opened, or the file cannot be written any more.
    }
  } catch (...) {
  }
  direct_.reset();
  structure_.reset();
  open_step_.reset();
  open_.reset();
  std::rethrow_exception(located);
}

std::string JobSession::results_for_reading(const Job&) {
  // A static or full transient has written every solved step already; the others run whole.
  if (open_ && !direct_) close_open();
  return results_path();
}

void JobSession::finish(const Job&) {
  close_open();
}

void JobSession::complete() {
  close_open();
  share_generated_superelements();
}

std::vector<std::string> JobSession::results_files() const {
  std::vector<std::string> out = closed_files_;
  if (writer_) out.push_back(writer_->path());
  return out;
}

void JobSession::clear(const Job&) {
  close_open();
  if (owned_writer_) {
    closed_files_.push_back(owned_writer_->path());
    owned_writer_.reset();  // the file is closed and complete
    writer_ = nullptr;
  }
  job_lock_.reset();
  superseded_files_ = 0;
  new_analysis_.reset();
  superelement_expansion_job_ = false;
  reduced_state_.reset();  // an expansion pass cannot refer to a solution of the job before
  models_.clear();
  job_first_analysis_ = stats_.analyses.size();
}

void run_job(const Job& job, const std::string& jobname, const RunSettings& settings,
             ResultsWriter& writer, RunStatistics& stats) {
  JobSession session(writer, jobname, settings, stats);
  for (std::size_t i = 0; i < job.steps.size(); ++i) session.solve(job, i);
  session.finish(job);
}

}  // namespace impactfe
