#include "results/live_writers.h"

#include <filesystem>
#include <map>
#include <mutex>
#include <stdexcept>
#include <utility>

#include "core/log.h"

namespace impactfe {

namespace {

/// The file a path names.
std::string file_key(const std::string& path) {
  std::error_code ec;
  const auto p = std::filesystem::weakly_canonical(std::filesystem::absolute(path), ec);
  return ec ? path : p.string();
}

struct LiveWriters {
  std::mutex mutex;
  std::map<std::string, std::pair<const void*, std::function<void()>>> by_file;  // owner, sync
};

LiveWriters& live_writers() {
  static LiveWriters w;
  return w;
}

}  // namespace

void register_live_writer(const std::string& path, const void* owner, std::function<void()> sync) {
  LiveWriters& w = live_writers();
  std::lock_guard<std::mutex> lock(w.mutex);
  w.by_file[file_key(path)] = {owner, std::move(sync)};
}

void unregister_live_writer(const std::string& path, const void* owner) {
  LiveWriters& w = live_writers();
  std::lock_guard<std::mutex> lock(w.mutex);
  auto it = w.by_file.find(file_key(path));
  if (it != w.by_file.end() && it->second.first == owner) w.by_file.erase(it);
}

void sync_live_writer(const std::string& path) {
  LiveWriters& w = live_writers();
  std::lock_guard<std::mutex> lock(w.mutex);
  auto it = w.by_file.find(file_key(path));
  if (it == w.by_file.end()) return;
  try {
    it->second.second();
  } catch (const std::exception& e) {
    // The writer reports the failure itself at its next append or when it closes.
    Log::debug("results file {}: sync for a reader failed: {}", path, e.what());
  }
}

}  // namespace impactfe
