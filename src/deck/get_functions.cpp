#include "deck/get_functions.h"

#include <fmt/format.h>

#include <cmath>

#include "deck/post_support.h"

namespace impactfe::deck {

namespace {

constexpr const char* kLabels[] = {"UX", "UY", "UZ", "ROTX", "ROTY", "ROTZ",
                                   "VX", "VY", "VZ", "AX",   "AY",   "AZ"};

/// Value of result `label` at node `arg` in the current set. The results layer reports a
/// missing node or an unexpanded slave DOF as an InputError without a deck location; inside an
/// expression it becomes an ExpressionError, which the calling command reports with its line.
double nodal_function(DeckReader& r, const char* label, double arg) {
  if (!std::isfinite(arg) || std::fabs(arg) > 2e9)
    throw ExpressionError(fmt::format("{}: bad node number", label));
  const int node = static_cast<int>(std::lround(arg));
  Command c;
  c.name = label;
  c.where.command = label;
  try {
    return nodal_result(r, c, node, label);
  } catch (const InputError& e) {
    throw ExpressionError(fmt::format("{}({}): {}", label, node, e.message()));
  }
}

template <int K>
double f_result(DeckReader& r, const std::vector<double>& a) {
  return nodal_function(r, kLabels[K], a[0]);
}

}  // namespace

void register_results_get_functions(std::vector<GetFunctionSpec>& t) {
  t.push_back({kLabels[0], 1, 1, f_result<0>});
  t.push_back({kLabels[1], 1, 1, f_result<1>});
  t.push_back({kLabels[2], 1, 1, f_result<2>});
  t.push_back({kLabels[3], 1, 1, f_result<3>});
  t.push_back({kLabels[4], 1, 1, f_result<4>});
  t.push_back({kLabels[5], 1, 1, f_result<5>});
  t.push_back({kLabels[6], 1, 1, f_result<6>});
  t.push_back({kLabels[7], 1, 1, f_result<7>});
  t.push_back({kLabels[8], 1, 1, f_result<8>});
  t.push_back({kLabels[9], 1, 1, f_result<9>});
  t.push_back({kLabels[10], 1, 1, f_result<10>});
  t.push_back({kLabels[11], 1, 1, f_result<11>});
}

}  // namespace impactfe::deck
