#pragma once
/// The claim a run makes on the files of a job before it touches any of them: <jobname>.lock
/// beside them, as MAPDL's, held with an exclusive flock for as long as the run uses the job
/// (docs/reliability.md, "Results files are never lost"). A second run with the same jobname in
/// the same directory is refused at once, naming the process that holds the job, instead of
/// truncating the log, the results file or the restart file of the first.
#include <memory>
#include <stdexcept>
#include <string>

namespace impactfe {

/// The lock file of the job whose results file is `results_path` (`dir/name.h5` →
/// `dir/name.lock`; a path without .h5 takes .lock appended).
std::string job_lock_path(const std::string& results_path);

/// One held lock. Several holders in one process share it (a run locks its jobname at start
/// and again when its session creates the results file); the last one releases it, which
/// removes the lock file. The lock of a process that dies is released by the system; the file
/// it leaves is taken over by the next run.
class JobLock {
 public:
  ~JobLock();
  JobLock(const JobLock&) = delete;
  JobLock& operator=(const JobLock&) = delete;
  const std::string& path() const { return path_; }

  /// Takes the lock of the job of `results_path` (job_lock_path), or shares the one this process
  /// already holds. Throws JobLockedError when another process holds it, std::runtime_error when
  /// the lock file cannot be created (a read-only directory: the run could not write its
  /// results either).
  static std::shared_ptr<JobLock> acquire(const std::string& results_path);

 private:
  JobLock(std::string path, int fd) : path_(std::move(path)), fd_(fd) {}
  std::string path_;
  int fd_ = -1;
};

/// Another running process holds the job (exit status 1: choose another jobname or directory).
class JobLockedError : public std::runtime_error {
 public:
  JobLockedError(const std::string& lock_path, long holder);
  long holder() const { return holder_; }  // its process id; 0 when the file does not say

 private:
  long holder_;
};

}  // namespace impactfe
