#pragma once
/// The one logger. Libraries never print; they log here. The CLI decides where the log goes
/// (run log file and, for warnings, the terminal).
#include <fmt/format.h>

#include <functional>
#include <string>
#include <vector>

namespace impactfe {

enum class LogLevel { Debug = 0, Info = 1, Warning = 2, Error = 3 };

class Log {
 public:
  using Sink = std::function<void(LogLevel, const std::string&)>;
  static void set_sink(Sink sink);
  static void write(LogLevel level, const std::string& message);
  /// Warnings issued so far (the run summary lists them).
  static const std::vector<std::string>& warnings();
  static void clear();

  template <typename... Args>
  static void info(fmt::format_string<Args...> f, Args&&... args) {
    write(LogLevel::Info, fmt::format(f, std::forward<Args>(args)...));
  }
  template <typename... Args>
  static void warn(fmt::format_string<Args...> f, Args&&... args) {
    write(LogLevel::Warning, fmt::format(f, std::forward<Args>(args)...));
  }
  template <typename... Args>
  static void debug(fmt::format_string<Args...> f, Args&&... args) {
    write(LogLevel::Debug, fmt::format(f, std::forward<Args>(args)...));
  }
};

}  // namespace impactfe
