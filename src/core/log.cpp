#include "core/log.h"

#include <mutex>

namespace impactfe {

namespace {
std::mutex g_mutex;
Log::Sink g_sink;
std::vector<std::string> g_warnings;
}  // namespace

void Log::set_sink(Sink sink) {
  std::lock_guard lock(g_mutex);
  g_sink = std::move(sink);
}

void Log::write(LogLevel level, const std::string& message) {
  std::lock_guard lock(g_mutex);
  if (level == LogLevel::Warning) g_warnings.push_back(message);
  if (g_sink) g_sink(level, message);
}

const std::vector<std::string>& Log::warnings() {
  return g_warnings;
}

void Log::clear() {
  std::lock_guard lock(g_mutex);
  g_warnings.clear();
}

}  // namespace impactfe
