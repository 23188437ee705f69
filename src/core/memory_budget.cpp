#include "core/memory_budget.h"

#include <fmt/format.h>
#include <unistd.h>

#include <atomic>
#include <cctype>
#include <cmath>
#include <fstream>
#include <limits>
#include <sstream>

namespace impactfe {

namespace {

std::atomic<double> limit_bytes{-1.0};

/// The first number of a one-line file ("max" and unreadable: nullopt).
std::optional<double> number_in(const std::string& path) {
  std::ifstream in(path);
  std::string text;
  if (!(in >> text) || text.empty() || !std::isdigit(static_cast<unsigned char>(text[0])))
    return std::nullopt;
  try {
    return std::stod(text);
  } catch (...) {
    return std::nullopt;
  }
}

std::optional<double> mem_available() {
  std::ifstream in("/proc/meminfo");
  std::string key;
  double kb = 0.0;
  std::string unit;
  while (in >> key >> kb >> unit)
    if (key == "MemAvailable:") return kb * 1024.0;
  return std::nullopt;
}

/// What the cgroup (v2, else v1) still allows.
std::optional<double> cgroup_room() {
  if (const auto max = number_in("/sys/fs/cgroup/memory.max"))
    if (const auto used = number_in("/sys/fs/cgroup/memory.current")) return *max - *used;
  if (const auto max = number_in("/sys/fs/cgroup/memory/memory.limit_in_bytes"))
    if (*max < 1e18)  // v1 reports "no limit" as a huge number
      if (const auto used = number_in("/sys/fs/cgroup/memory/memory.usage_in_bytes"))
        return *max - *used;
  return std::nullopt;
}

/// Resident bytes of this process.
double resident_bytes() {
  std::ifstream in("/proc/self/statm");
  double pages_total = 0.0, pages_resident = 0.0;
  if (!(in >> pages_total >> pages_resident)) return 0.0;
  return pages_resident * static_cast<double>(::sysconf(_SC_PAGESIZE));
}

}  // namespace

void set_memory_limit(std::optional<double> bytes) {
  limit_bytes.store(bytes ? *bytes : -1.0);
}

std::optional<double> memory_limit() {
  const double b = limit_bytes.load();
  return b >= 0.0 ? std::optional<double>(b) : std::nullopt;
}

MemoryAvailable memory_available() {
  MemoryAvailable out{std::numeric_limits<double>::infinity(), "no limit known"};
  const auto take = [&out](std::optional<double> bytes, const std::string& source) {
    if (bytes && *bytes < out.bytes) out = {std::max(0.0, *bytes), source};
  };
  take(mem_available(), "MemAvailable of /proc/meminfo");
  take(cgroup_room(), "the cgroup's memory limit");
  if (const auto limit = memory_limit())
    take(*limit - resident_bytes(), "--memory " + format_bytes(*limit));
  return out;
}

void require_memory(double bytes, const std::string& what, const std::string& fits) {
  const MemoryAvailable available = memory_available();
  if (bytes <= available.bytes) return;
  throw MemoryLimitError(
      fmt::format("{} needs about {}, more than the {} this run may still "
                  "take ({}){}",
                  what, format_bytes(bytes), format_bytes(available.bytes), available.source,
                  fits.empty() ? "" : ": " + fits));
}

std::string format_bytes(double bytes) {
  if (bytes >= 1e9) return fmt::format("{:.3g} GB", bytes / 1e9);
  if (bytes >= 1e6) return fmt::format("{:.3g} MB", bytes / 1e6);
  return fmt::format("{:.3g} kB", bytes / 1e3);
}

std::optional<double> parse_bytes(const std::string& text) {
  std::istringstream in(text);
  double value = 0.0;
  if (!(in >> value) || !(value > 0.0) || !std::isfinite(value)) return std::nullopt;
  std::string unit;
  in >> unit;
  for (auto& ch : unit) ch = static_cast<char>(std::toupper(static_cast<unsigned char>(ch)));
  if (unit == "B") unit.clear();
  if (unit.size() == 2 && unit[1] == 'B') unit.pop_back();
  const double scale = unit.empty()  ? 1.0
                       : unit == "K" ? 1e3
                       : unit == "M" ? 1e6
                       : unit == "G" ? 1e9
                       : unit == "T" ? 1e12
                                     : 0.0;
  if (scale == 0.0) return std::nullopt;
  return value * scale;
}

}  // namespace impactfe
