#include "analysis/generalized_history.h"

#include <fmt/format.h>
#include <sys/types.h>

#include <algorithm>
#include <cerrno>
#include <cmath>
#include <cstring>
#include <filesystem>
#include <system_error>

#include "core/errors.h"
#include "core/memory_budget.h"

namespace impactfe {

GeneralizedHistory::GeneralizedHistory(int n_coordinates, int n_gaps, std::size_t block_bytes)
    : nq_(n_coordinates),
      ng_(n_gaps),
      record_(3 * static_cast<std::size_t>(n_coordinates) + static_cast<std::size_t>(n_gaps)) {
  block_points_ = std::max<std::size_t>(1, block_bytes / (8 * std::max<std::size_t>(record_, 1)));
  block_.reserve(block_points_ * record_);
}

std::size_t GeneralizedHistory::default_block_bytes() {
  constexpr double kMin = 64.0 * 1024, kMax = 32.0 * 1024 * 1024;
  return static_cast<std::size_t>(std::clamp(memory_available().bytes / 64.0, kMin, kMax));
}

double GeneralizedHistory::bytes_per_point(int n_coordinates, int n_gaps) {
  return 8.0 * (3.0 * n_coordinates + n_gaps);
}

void GeneralizedHistory::require_disk_space(double n_points, int n_coordinates, int n_gaps) {
  std::error_code ec;
  const std::filesystem::path dir = std::filesystem::temp_directory_path(ec);
  if (ec) return;  // no temporary directory to measure: the first block write will say so
  const std::filesystem::space_info space = std::filesystem::space(dir, ec);
  if (ec) return;
  const double per_point = bytes_per_point(n_coordinates, n_gaps);
  const double needed = n_points * per_point;
  const auto available = static_cast<double>(space.available);
  if (needed <= available) return;
  throw MemoryLimitError(fmt::format(
      "the {:.0f} time points of this reduced / mode-superposition transient keep their history "
      "({:.0f} bytes each, for the expansion pass) in a temporary file of about {}, more than "
      "the {} free in {}; at most about {:.0f} points fit: a larger DELTIM, a shorter TIME, or "
      "TMPDIR on a larger disk",
      n_points, per_point, format_bytes(needed), format_bytes(available), dir.string(),
      std::floor(available / per_point)));
}

void GeneralizedHistory::append(const VectorXd& q, const VectorXd& v, const VectorXd& a,
                                const VectorXd& gap_forces) {
  IMPACTFE_CHECK(q.size() == nq_ && v.size() == nq_ && a.size() == nq_ && gap_forces.size() == ng_,
                 "GeneralizedHistory::append: the state does not match the history's sizes");
  if (n_in_block_ == block_points_) flush_block();
  block_.insert(block_.end(), q.data(), q.data() + nq_);
  block_.insert(block_.end(), v.data(), v.data() + nq_);
  block_.insert(block_.end(), a.data(), a.data() + nq_);
  block_.insert(block_.end(), gap_forces.data(), gap_forces.data() + ng_);
  ++n_in_block_;
}

void GeneralizedHistory::flush_block() {
  if (!file_) {
    file_.reset(std::tmpfile());
    if (!file_)
      throw SolutionError(fmt::format(
          "reduced / mode-superposition transient: cannot create the temporary file for the "
          "state history ({}); set TMPDIR to a writable directory",
          std::strerror(errno)));
  }
  // Appends at the end: reads (at) move the position.
  if (fseeko(file_.get(), 0, SEEK_END) != 0 ||
      std::fwrite(block_.data(), sizeof(double), block_.size(), file_.get()) != block_.size() ||
      std::fflush(file_.get()) != 0)
    throw SolutionError(fmt::format(
        "reduced / mode-superposition transient: writing the state history after {} points to "
        "its temporary file failed ({}); the points computed so far are in the results file",
        n_on_file_, std::strerror(errno)));
  n_on_file_ += n_in_block_;
  n_in_block_ = 0;
  block_.clear();
}

GeneralizedHistory::Record GeneralizedHistory::at(std::size_t k) const {
  IMPACTFE_CHECK(k < size(), fmt::format("GeneralizedHistory::at: point {} of {}", k, size()));
  std::vector<double> file_record;
  const double* r = nullptr;
  if (k >= n_on_file_) {
    r = block_.data() + (k - n_on_file_) * record_;
  } else {
    file_record.resize(record_);
    const auto offset = static_cast<off_t>(k * record_ * sizeof(double));
    if (fseeko(file_.get(), offset, SEEK_SET) != 0 ||
        std::fread(file_record.data(), sizeof(double), record_, file_.get()) != record_)
      throw SolutionError(fmt::format(
          "reduced / mode-superposition transient: reading point {} of the state history back "
          "from its temporary file failed ({})",
          k, std::strerror(errno)));
    r = file_record.data();
  }
  Record out;
  out.q = Eigen::Map<const VectorXd>(r, nq_);
  out.v = Eigen::Map<const VectorXd>(r + nq_, nq_);
  out.a = Eigen::Map<const VectorXd>(r + 2 * nq_, nq_);
  out.gap_forces = Eigen::Map<const VectorXd>(r + 3 * nq_, ng_);
  return out;
}

}  // namespace impactfe
