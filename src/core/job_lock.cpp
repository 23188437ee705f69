#include "core/job_lock.h"

#include <fcntl.h>
#include <sys/file.h>
#include <sys/stat.h>
#include <unistd.h>

#include <cerrno>
#include <chrono>
#include <cstring>
#include <filesystem>
#include <map>
#include <mutex>
#include <string>
#include <thread>

namespace impactfe {

namespace {

std::mutex registry_mutex;
/// The locks this process holds, by absolute lock-file path: a second flock of the same file
/// from this process would conflict with the first (flock locks belong to open files).
std::map<std::string, std::weak_ptr<JobLock>>& registry() {
  static std::map<std::string, std::weak_ptr<JobLock>> held;
  return held;
}

/// The process id written in a lock file (0 when unreadable). The holder writes it just after
/// taking the lock: a run started at the same moment can find the lock taken and the file still
/// empty, so an empty file is read again for up to 0.2 s before the holder is called unknown.
long holder_of(const std::string& path) {
  for (int attempt = 0; attempt < 20; ++attempt) {
    const int fd = ::open(path.c_str(), O_RDONLY | O_CLOEXEC);
    if (fd < 0) return 0;
    char text[32] = {};
    const ssize_t n = ::read(fd, text, sizeof(text) - 1);
    ::close(fd);
    if (n > 0) return std::strtol(text, nullptr, 10);
    std::this_thread::sleep_for(std::chrono::milliseconds(10));
  }
  return 0;
}

std::string absolute_path(const std::string& path) {
  std::error_code ec;
  const auto abs = std::filesystem::absolute(path, ec);
  return ec ? path : abs.lexically_normal().string();
}

}  // namespace

std::string job_lock_path(const std::string& results_path) {
  const std::string ext = ".h5";
  const bool has_ext = results_path.size() > ext.size() &&
                       results_path.compare(results_path.size() - ext.size(), ext.size(), ext) == 0;
  return (has_ext ? results_path.substr(0, results_path.size() - ext.size()) : results_path) +
         ".lock";
}

JobLockedError::JobLockedError(const std::string& lock_path, long holder)
    : std::runtime_error(
          holder > 0 ? "another run (process " + std::to_string(holder) +
                           ") is using this job: " + lock_path +
                           " is locked; wait for that run to end, or give this run another jobname "
                           "(-j, /FILNAME) or output directory (-o)"
                     : "another run is using this job: " + lock_path +
                           " is locked; wait for that run to end, or give this run another jobname "
                           "(-j, /FILNAME) or output directory (-o)"),
      holder_(holder) {}

JobLock::~JobLock() {
  std::lock_guard guard(registry_mutex);
  registry().erase(path_);
  // Removed while still locked: a run that opened the file meanwhile finds, once it has the
  // lock, that the name no longer leads to its file and starts again (acquire).
  ::unlink(path_.c_str());
  ::close(fd_);
}

std::shared_ptr<JobLock> JobLock::acquire(const std::string& results_path) {
  const std::string path = absolute_path(job_lock_path(results_path));
  std::lock_guard guard(registry_mutex);
  if (auto held = registry()[path].lock()) return held;
  for (int attempt = 0; attempt < 100; ++attempt) {
    const int fd = ::open(path.c_str(), O_RDWR | O_CREAT | O_CLOEXEC, 0644);
    if (fd < 0)
      throw std::runtime_error("cannot create the lock file " + path + ": " + std::strerror(errno));
    if (::flock(fd, LOCK_EX | LOCK_NB) != 0) {
      const int err = errno;
      ::close(fd);
      if (err == EWOULDBLOCK) throw JobLockedError(path, holder_of(path));
      throw std::runtime_error("cannot lock " + path + ": " + std::strerror(err));
    }
    // The holder before may have removed the file between our open and our flock: the lock is
    // ours only if the name still leads to the file we locked.
    struct stat opened {};
    struct stat named {};
    if (::fstat(fd, &opened) != 0 || ::stat(path.c_str(), &named) != 0 ||
        opened.st_ino != named.st_ino || opened.st_dev != named.st_dev) {
      ::close(fd);
      continue;
    }
    const std::string pid = std::to_string(static_cast<long>(::getpid())) + "\n";
    if (::ftruncate(fd, 0) != 0 || ::pwrite(fd, pid.data(), pid.size(), 0) < 0) {
      // The lock holds without the process id; a refused run then names no process.
    }
    std::shared_ptr<JobLock> lock(new JobLock(path, fd));
    registry()[path] = lock;
    return lock;
  }
  throw std::runtime_error("cannot lock " + path + ": it keeps being replaced");
}

}  // namespace impactfe
