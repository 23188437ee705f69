// ResultsWriter: the results file written off the solver's thread (issue 11: "results writing
// buffered and off the critical path").
//
// The thesis helmet spent a fifth of its run in HDF5: creating the file and writing the model
// section, then storing 191 points. Here the analysis hands each operation, with its data, to
// a writer thread that performs them in order on a ResultsFileWriter, and goes on solving. So
// the file holds the same bytes as when written on the solver's thread: the same calls in the
// same order (only the syncs that come every 0.1 s fall where the clock says, as before).
//
// - When (WriterThread, results_file.h): `auto` when the run may use two threads and a core is
//   idle as the file is created, since handing the points over costs CPU time (page faults of
//   the writer's own malloc arena, wake-ups) that only an idle core pays back; and it retires
//   when writing turns out to be the bottleneck (kFullQueuesToRetire). Without a thread every
//   operation runs at once on the caller's.
// - Debian's HDF5 is built thread-safe (one lock around its API): a reader or a superelement
//   file of the analysis's thread is safe beside it.
// - The queue holds at most kQueueBytes of point data beyond the point being written (always
//   one point): a large model's points wait for the writer rather than pile up in memory.
// - A failure on the writer thread (a full disk) is kept and rethrown by the next call of the
//   analysis, and by every call after it. end_analysis waits for the writer, so an analysis
//   that completes has its results written or reports why not; a reader of the file in this
//   process (POST1, POST26, *GET) waits for every point appended so far (live_writers.h).
// - A file that cannot be created is reported by the constructor, as before: the system's
//   reason comes from opening it here first.
#include <fcntl.h>
#include <fmt/format.h>
#include <unistd.h>

#include <atomic>
#include <cerrno>
#include <chrono>
#include <condition_variable>
#include <cstring>
#include <deque>
#include <functional>
#include <mutex>
#include <thread>

#include "core/errors.h"
#include "core/thread_pool.h"
#include "io/h5_util.h"
#include "results/live_writers.h"
#include "results/results_file_writer.h"

namespace impactfe {

namespace {

/// Point data queued for the writer beyond the point it is writing. A caller that finds the
/// queue full waits until it is half empty: when writing is the bottleneck (link_bar_1024,
/// 602 points of 200 kB), a wake-up per point cost more than the overlap saved.
constexpr double kQueueBytes = 2.0 * 1024 * 1024;
/// The writer looks at its queue this often, and is woken when the queue holds kWakeBytes.
/// Waking it at every point cost the thesis helmet's solver thread 11 ms in 191 futex calls
/// (50-60 µs each on this 2-vCPU VM: the other vCPU sleeps and is kicked by the hypervisor).
constexpr auto kPollPeriod = std::chrono::milliseconds(20);
constexpr double kWakeBytes = 0.5 * 1024 * 1024;
/// In `auto` mode, the caller that has found the queue full this many times writes on its own
/// thread from then on: writing is the bottleneck, and the thread adds only the handing over
/// (link_bar_1024: 4 % slower with it, and 3.5 MB more at its peak).
constexpr int kFullQueuesToRetire = 8;

/// Bytes of a time point's values (what its copy in the queue holds).
double point_bytes(const TimePoint& p) {
  double values =
      static_cast<double>(p.displacement.size() + p.velocity.size() + p.acceleration.size() +
                          p.reaction.size() + p.gap_forces.size());
  for (const auto& [family, table] : p.element_results)
    values += static_cast<double>(table.values.size() + table.element_ids.size());
  return 8.0 * values;
}

std::atomic<WriterThread> writer_thread_mode{WriterThread::Auto};

/// Whether this process may call HDF5 from two threads.
bool hdf5_thread_safe() {
  hbool_t safe = false;
  return H5is_library_threadsafe(&safe) >= 0 && safe;
}

}  // namespace

ResultsModelSection ResultsModelSection::of(const Model& model) {
  ResultsModelSection m;
  m.title = model.title;
  m.jobname = model.jobname;
  m.units = model.units;
  for (const auto& [id, node] : model.nodes) {
    m.node_ids.push_back(id);
    m.node_xyz.insert(m.node_xyz.end(), {node.x.x(), node.x.y(), node.x.z()});
  }
  for (const auto& [id, e] : model.elements) {
    m.element_ids.push_back(id);
    m.element_types.push_back(e.type);
    m.element_materials.push_back(e.mat);
    m.element_reals.push_back(e.real);
    auto t = model.element_types.find(e.type);
    m.element_type_names.push_back(t == model.element_types.end() ? std::string()
                                                                  : t->second.ansys_name);
    m.element_nodes.push_back(e.nodes);
  }
  return m;
}

struct ResultsWriter::Impl {
  std::string path;
  std::vector<int> node_ids;
  int n_analyses = 0;
  bool analysis_open = false;
  /// The file's writer: created, used and destroyed by the writer thread when there is one.
  std::unique_ptr<ResultsFileWriter> file;

  struct Task {
    std::function<void()> run;
    double bytes = 0.0;
    bool after_failure = false;  // performed also after the writer failed (closing the file)
  };
  std::mutex mutex;
  std::condition_variable work_ready, work_done;
  std::deque<Task> tasks;
  double queued_bytes = 0.0;
  bool busy = false;         // the writer is performing a task
  bool room_wanted = false;  // the caller waits for room in the queue
  bool adaptive = false;     // `auto`: the thread retires when writing is the bottleneck
  int full_queues = 0;       // times the caller found the queue full
  bool stopping = false;     // no task comes any more
  std::exception_ptr error;
  std::thread writer;

  bool background() const { return writer.joinable(); }
  /// Starts the writer thread when the run allows two threads and HDF5 two callers; with no
  /// thread to be had, the operations run on the caller's thread.
  void start();
  /// Closes the file on the writer thread, after its tasks, and ends the thread.
  void stop();
  /// Ends the thread once it has performed every task; the caller's thread writes from then
  /// on. Rethrows the writer's failure.
  void retire();
  void work();
  /// Performs `run` on the writer thread after the tasks before it (at once without one);
  /// rethrows an earlier failure of the writer. `bytes`: the data `run` holds.
  void post(std::function<void()> run, double bytes = 0.0);
  /// Waits until the writer has performed every task; rethrows its failure.
  void wait_idle();
};

void ResultsWriter::Impl::work() {
  h5::silence_errors();  // the thread-safe HDF5 keeps its error reporting per thread
  std::unique_lock lock(mutex);
  for (;;) {
    while (!stopping && tasks.empty()) work_ready.wait_for(lock, kPollPeriod);
    if (tasks.empty()) return;
    Task task = std::move(tasks.front());
    tasks.pop_front();
    queued_bytes -= task.bytes;
    busy = true;
    if (room_wanted && queued_bytes <= 0.5 * kQueueBytes) work_done.notify_all();
    const bool skip = error != nullptr && !task.after_failure;
    lock.unlock();
    std::exception_ptr failure;
    if (!skip) {
      try {
        task.run();
      } catch (...) {
        failure = std::current_exception();
      }
    }
    task.run = nullptr;  // the task's data go before the lock is taken again
    lock.lock();
    if (failure && !error) error = failure;
    busy = false;
    // The caller waits for an empty queue (wait_idle) or for room: woken only then, not at
    // every task (each wake-up is a system call on both sides).
    if (tasks.empty() || error) work_done.notify_all();
  }
}

void ResultsWriter::Impl::start() {
  const WriterThread mode = writer_thread_mode.load();
  if (mode == WriterThread::Off || !hdf5_thread_safe()) return;
  adaptive = mode == WriterThread::Auto;
  if (adaptive && (threads::max_threads() < 2 || !threads::core_idle())) return;
  try {
    writer = std::thread([this] { work(); });
  } catch (const std::system_error&) {
  }
}

void ResultsWriter::Impl::stop() {
  if (!background()) return;
  {
    std::lock_guard lock(mutex);
    // Also after a failure: the file writer then leaves the file in its last flushed state.
    tasks.push_back({[this] { file.reset(); }, 0.0, true});
    stopping = true;
    work_ready.notify_one();
  }
  writer.join();
}

void ResultsWriter::Impl::retire() {
  {
    std::unique_lock lock(mutex);
    work_ready.notify_one();
    work_done.wait(lock, [&] { return tasks.empty() && !busy; });
    stopping = true;
    work_ready.notify_one();
  }
  writer.join();
  if (error) std::rethrow_exception(error);
}

void ResultsWriter::Impl::post(std::function<void()> run, double bytes) {
  if (!background()) {
    run();
    return;
  }
  std::unique_lock lock(mutex);
  if (!tasks.empty() && queued_bytes + bytes > kQueueBytes) {
    room_wanted = true;
    work_ready.notify_one();
    work_done.wait(lock, [&] { return error || queued_bytes <= 0.5 * kQueueBytes; });
    room_wanted = false;
    if (!error && adaptive && ++full_queues == kFullQueuesToRetire) {
      lock.unlock();
      retire();
      run();
      return;
    }
  }
  if (error) std::rethrow_exception(error);
  tasks.push_back({std::move(run), bytes});
  queued_bytes += bytes;
  if (queued_bytes >= kWakeBytes) work_ready.notify_one();
}

void ResultsWriter::Impl::wait_idle() {
  if (!background()) return;
  std::unique_lock lock(mutex);
  work_ready.notify_one();
  work_done.wait(lock, [&] { return tasks.empty() && !busy; });
  if (error) std::rethrow_exception(error);
}

void set_results_writer_thread(WriterThread mode) {
  writer_thread_mode.store(mode);
}

ResultsWriter::ResultsWriter(const std::string& path, const Model& model)
    : impl_(std::make_unique<Impl>()) {
  h5::silence_errors();  // this thread writes too once the writer thread retires
  Impl& m = *impl_;
  m.path = path;
  // Exit status 2 (the run cannot keep its results), with the system's reason, now rather than
  // at a later step: HDF5 creates the file on the writer thread (under this temporary name,
  // renamed over `path` once it holds the model: ResultsFileWriter).
  const std::string creating = path + ".creating";
  const int fd = ::open(creating.c_str(), O_WRONLY | O_CREAT | O_CLOEXEC, 0666);
  if (fd < 0)
    throw SolutionError(
        fmt::format("cannot create results file '{}': {}", path, std::strerror(errno)));
  ::close(fd);
  auto section = std::make_shared<ResultsModelSection>(ResultsModelSection::of(model));
  m.node_ids = section->node_ids;
  m.start();
  m.post([&m, section] { m.file = std::make_unique<ResultsFileWriter>(m.path, *section); });
  register_live();
}

ResultsWriter::ResultsWriter(const std::string& path, Append) : impl_(std::make_unique<Impl>()) {
  // A continued file is opened here: its node ids and analyses are needed at once.
  h5::silence_errors();
  Impl& m = *impl_;
  m.path = path;
  m.file = std::make_unique<ResultsFileWriter>(path, Append{});
  m.node_ids = m.file->node_ids();
  m.n_analyses = m.file->n_analyses();
  m.start();
  register_live();
}

void ResultsWriter::register_live() {
  // A reader of the file in this process first waits for every point appended so far.
  Impl& m = *impl_;
  try {
    register_live_writer(m.path, this, [&m] {
      m.post([&m] { m.file->sync_for_reader(); });
      m.wait_idle();
    });
  } catch (...) {
    m.stop();
    throw;
  }
}

ResultsWriter::~ResultsWriter() {
  unregister_live_writer(impl_->path, this);
  impl_->stop();  // without a writer thread, `file` closes with impl_
}

int ResultsWriter::begin_analysis(ResultsKind kind, const std::string& description,
                                  long long expected_points) {
  Impl& m = *impl_;
  m.post([&m, kind, description, expected_points] {
    m.file->begin_analysis(kind, description, expected_points);
  });
  m.analysis_open = true;
  return ++m.n_analyses;
}

void ResultsWriter::append(const TimePoint& point) {
  append(TimePoint(point));
}

void ResultsWriter::append(TimePoint&& point) {
  Impl& m = *impl_;
  const double bytes = point_bytes(point);
  auto shared = std::make_shared<const TimePoint>(std::move(point));
  m.post([&m, shared] { m.file->append(*shared); }, bytes);
}

void ResultsWriter::set_sparse_output(bool sparse) {
  Impl& m = *impl_;
  m.post([&m, sparse] { m.file->set_sparse_output(sparse); });
}

void ResultsWriter::write_modes(const std::vector<double>& frequencies_hz,
                                const std::vector<Eigen::MatrixXd>& shapes) {
  Impl& m = *impl_;
  double bytes = 8.0 * static_cast<double>(frequencies_hz.size());
  for (const auto& s : shapes) bytes += 8.0 * static_cast<double>(s.size());
  m.post([&m, frequencies_hz, shapes] { m.file->write_modes(frequencies_hz, shapes); }, bytes);
}

void ResultsWriter::set_attribute(const std::string& name, double value) {
  Impl& m = *impl_;
  m.post([&m, name, value] { m.file->set_attribute(name, value); });
}

void ResultsWriter::set_attribute(const std::string& name, const std::string& value) {
  Impl& m = *impl_;
  m.post([&m, name, value] { m.file->set_attribute(name, value); });
}

void ResultsWriter::set_count(const std::string& name, long long value) {
  Impl& m = *impl_;
  m.post([&m, name, value] { m.file->set_count(name, value); });
}

void ResultsWriter::set_element_nodes(const std::map<int, std::vector<int>>& nodes) {
  Impl& m = *impl_;
  m.post([&m, nodes] { m.file->set_element_nodes(nodes); });
}

void ResultsWriter::end_analysis(const std::string& status) {
  Impl& m = *impl_;
  // Checked here: a failure of the writer thread stays for every later call, and a session
  // that failed before its analysis began calls this once too many (JobSession::fail).
  IMPACTFE_CHECK(m.analysis_open, "ResultsWriter::end_analysis: no analysis is open");
  m.analysis_open = false;
  m.post([&m, status] { m.file->end_analysis(status); });
  m.wait_idle();
}

const std::vector<int>& ResultsWriter::node_ids() const {
  return impl_->node_ids;
}
const std::string& ResultsWriter::path() const {
  return impl_->path;
}

}  // namespace impactfe
