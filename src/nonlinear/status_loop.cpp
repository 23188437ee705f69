#include "nonlinear/status_loop.h"

#include <fmt/format.h>

#include <algorithm>

#include "core/log.h"

namespace impactfe {

StatusLoop::StatusLoop(const std::vector<std::unique_ptr<Element>>& elements,
                       const Assembler& assembler, int chatter_limit)
    : elements_(elements), assembler_(assembler), chatter_limit_(chatter_limit) {
  for (std::size_t e = 0; e < elements_.size(); ++e) {
    if (elements_[e]->has_status()) members_.push_back(e);
    if (elements_[e]->has_status() || elements_[e]->has_history()) committed_.push_back(e);
    has_history_ |= elements_[e]->has_history();
  }
}

void StatusLoop::begin_step() {
  flips_.clear();
}

int StatusLoop::update(const VectorXd& u, const StepLabel& where) {
  int changed = 0;
  for (std::size_t e : members_) {
    assembler_.gather(e, u, ue_);
    if (!elements_[e]->update_status(assembler_.context(), ue_)) continue;
    ++changed;
    ++n_changes_;
    if (++flips_[e] == chatter_limit_) {
      elements_[e]->freeze_status(true);
      if (!quiet_freeze_)
        Log::warn(
            "load step {} substep {} (t = {:g}): element {} changed status {} times (open/closed "
            "chatter); status frozen for the rest of the step. A smaller time step (DELTIM / "
            "DTIME) "
            "resolves the contact",
            where.load_step, where.substep, where.time, elements_[e]->id(), chatter_limit_);
    }
  }
  return changed;
}

int StatusLoop::settle(const VectorXd& u) {
  std::vector<bool> changed(elements_.size(), false);
  for (int pass = 0; pass < chatter_limit_; ++pass) {
    int n = 0;
    for (std::size_t e : members_) {
      assembler_.gather(e, u, ue_);
      if (!elements_[e]->update_status(assembler_.context(), ue_)) continue;
      changed[e] = true;
      ++n;
    }
    if (n == 0) break;
  }
  for (std::size_t e : members_) {
    assembler_.gather(e, u, ue_);
    elements_[e]->commit(ue_);
  }
  return static_cast<int>(std::count(changed.begin(), changed.end(), true));
}

void StatusLoop::end_step() {
  for (const auto& [e, count] : flips_)
    if (count >= chatter_limit_) elements_[e]->freeze_status(false);
}

void StatusLoop::commit(const VectorXd& u) {
  for (std::size_t e : committed_) {
    assembler_.gather(e, u, ue_);
    if (elements_[e]->has_status()) elements_[e]->commit(ue_);
    if (elements_[e]->has_history()) elements_[e]->commit_history(assembler_.context(), ue_);
  }
}

void StatusLoop::revert() {
  for (std::size_t e : committed_) elements_[e]->revert();
}

bool StatusLoop::chattered() const {
  for (const auto& [e, count] : flips_)
    if (count >= chatter_limit_) return true;
  return false;
}

std::string StatusLoop::chatter_report() const {
  std::string out;
  for (const auto& [e, count] : flips_)
    if (count >= 2) out += fmt::format(" {}({}x)", elements_[e]->id(), count);
  return out;
}

}  // namespace impactfe
