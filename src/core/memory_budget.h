#pragma once
/// How much more memory the run may take, and refusals of models that would not fit
/// (docs/reliability.md, "Memory"): the least of what the machine has available (MemAvailable
/// of /proc/meminfo), what the process's cgroup still allows (memory.max − memory.current), and
/// what `impactfe run --memory` leaves beyond what the process already uses.
#include <cstddef>
#include <optional>
#include <string>

#include "core/errors.h"

namespace impactfe {

/// The model needs more memory than the run may take (exit status 1: a smaller model, or more
/// memory). The message says what the model is, what it needs and what is available.
class MemoryLimitError : public ModelError {
 public:
  using ModelError::ModelError;
};

/// `impactfe run --memory`: the most the whole process may use (bytes; nullopt: no limit of
/// its own).
void set_memory_limit(std::optional<double> bytes);
std::optional<double> memory_limit();

/// Bytes the process may still take, and what bounds it ("MemAvailable", "cgroup limit",
/// "--memory 4G").
struct MemoryAvailable {
  double bytes = 0.0;
  std::string source;
};
MemoryAvailable memory_available();

/// Throws MemoryLimitError "<what> needs about X GB, more than the Y GB available (<source>)
/// <fits>" when `bytes` exceed memory_available(). `fits`: what would fit, or "".
void require_memory(double bytes, const std::string& what, const std::string& fits = {});

/// "1.5 GB", "820 MB", "12 kB".
std::string format_bytes(double bytes);
/// Parses "4G", "512M", "2.5GB", "1000000" (bytes); nullopt when not a size.
std::optional<double> parse_bytes(const std::string& text);

}  // namespace impactfe
