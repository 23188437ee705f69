#include "core/interruption.h"

#include <fmt/format.h>

#include <atomic>
#include <csignal>

namespace impactfe {

namespace {
// Lock-free atomics: the only shared state a signal handler may touch (C++17 [support.signal]).
std::atomic<int> g_stop_signal{0};
std::atomic<int> g_stop_points{0};
static_assert(std::atomic<int>::is_always_lock_free);
}  // namespace

int stop_requested() {
  return g_stop_signal.load();
}

void request_stop(int signal) {
  int none = 0;
  g_stop_signal.compare_exchange_strong(none, signal);
}

void clear_stop_request() {
  g_stop_signal.store(0);
}

bool stop_points_active() {
  return g_stop_points.load() > 0;
}

StopPoints::StopPoints() {
  ++g_stop_points;
}

StopPoints::~StopPoints() {
  --g_stop_points;
}

std::string signal_name(int signal) {
  if (signal == SIGINT) return "SIGINT";
  if (signal == SIGTERM) return "SIGTERM";
  return fmt::format("signal {}", signal);
}

}  // namespace impactfe
