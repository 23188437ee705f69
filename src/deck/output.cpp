#include "deck/output.h"

#include <algorithm>
#include <stdexcept>
#include <string_view>

#include "core/log.h"

namespace impactfe::deck {

void OutputSink::write(const std::string& text) {
  n_lines_ += std::count(text.begin(), text.end(), '\n');
  if (file_.is_open()) {
    file_ << text;
    file_.flush();  // a run that fails later keeps what was printed
  } else if (terminal_ != nullptr) {
    *terminal_ << text;
    terminal_->flush();
  } else {
    std::string_view lines(text);
    if (!lines.empty() && lines.back() == '\n') lines.remove_suffix(1);
    Log::info("output: {}", lines);
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
