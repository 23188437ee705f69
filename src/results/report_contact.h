#pragma once
/// Contact forces of the report: the total normal force (sum of FN) and the sum of the friction
/// forces (FT) of each contact pair over time. A pair is the real set its contact elements share
/// with their target (MAPDL's pair identifier); gaps (COMBIN40, CONTA178) are reported apart.
#include <map>
#include <utility>
#include <vector>

#include "results/results_file.h"

namespace impactfe {

class ContactForceSums {
 public:
  using Series = std::vector<std::pair<double, double>>;
  /// The contact elements (shape role Contact) of the file and their real sets.
  explicit ContactForceSums(const ResultsReader& reader);
  /// Adds the sums of one stored time point (tables without FN are skipped).
  void add(const TimePoint& p);
  struct Pair {
    int real = 0;
    int n_elements = 0;
    Series normal;    // (t, ΣFN)
    Series friction;  // (t, ΣFT)
  };
  /// Pairs in real-set order; empty when the file has no contact element results.
  std::vector<Pair> pairs() const;

 private:
  std::map<int, int> real_of_;  // contact element id -> real set
  std::map<int, Pair> pairs_;
};

}  // namespace impactfe
