#include "deck/output.h"

#include <stdexcept>

#include "core/log.h"

namespace impactfe::deck {

void OutputSink::print(const std::string& text) {
  std::size_t start = 0;
  for (;;) {
    const std::size_t end = text.find('\n', start);
    ++n_lines_;
    if (end == std::string::npos) break;
    start = end + 1;
  }
  if (file_.is_open()) {
    file_ << text << '\n';
    file_.flush();  // a run that fails later keeps what was printed
  } else if (terminal_ != nullptr) {
    *terminal_ << text << '\n';
    terminal_->flush();
  } else {
    Log::info("output: {}", text);
  }
}

void OutputSink::redirect(const std::string& path, bool append) {
  to_terminal();
  file_.open(path, append ? std::ios::app : std::ios::trunc);
  if (!file_) {
    file_.close();
    throw std::runtime_error("cannot open '" + path + "' for writing");
  }
  path_ = path;
}

void OutputSink::to_terminal() {
  if (file_.is_open()) file_.close();
  file_.clear();
  path_.clear();
}

}  // namespace impactfe::deck
