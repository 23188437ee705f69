#include "core/solution_control.h"

namespace impactfe {

SolutionControls& SolutionControls::instance() {
  static SolutionControls table;
  return table;
}

void SolutionControls::clear() {
  *this = SolutionControls{};
}

void SolutionControls::record(const SourceLocation& where, int number) {
  steps_[{where.file, where.line, number}] = current;
}

StepControl SolutionControls::step(const SourceLocation& where, int number) const {
  const auto it = steps_.find({where.file, where.line, number});
  return it == steps_.end() ? StepControl{} : it->second;
}

}  // namespace impactfe
