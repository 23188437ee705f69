// Encoding and sampling of the report's curves (report.h).
#include <cstdint>
#include <cstring>
#include <string>
#include <utility>
#include <vector>

#include "core/errors.h"
#include "results/report.h"

namespace impactfe {

/// Little-endian float32 values as base64 (NaN stays NaN): half the size of decimal text.
std::string float32_base64(const std::vector<double>& values) {
  static const char* alphabet = "ABCDEFGHIJKLMNOPQRSTUVWXYZabcdefghijklmnopqrstuvwxyz0123456789+/";
  std::vector<unsigned char> bytes(values.size() * 4);
  for (std::size_t i = 0; i < values.size(); ++i) {
    const float f = static_cast<float>(values[i]);
    std::uint32_t u = 0;
    std::memcpy(&u, &f, 4);
    for (int b = 0; b < 4; ++b) bytes[i * 4 + b] = static_cast<unsigned char>(u >> (8 * b));
  }
  std::string out;
  out.reserve((bytes.size() + 2) / 3 * 4);
  for (std::size_t i = 0; i < bytes.size(); i += 3) {
    const std::uint32_t n = (bytes[i] << 16) | (i + 1 < bytes.size() ? bytes[i + 1] << 8 : 0) |
                            (i + 2 < bytes.size() ? bytes[i + 2] : 0);
    out += alphabet[(n >> 18) & 63];
    out += alphabet[(n >> 12) & 63];
    out += i + 1 < bytes.size() ? alphabet[(n >> 6) & 63] : '=';
    out += i + 2 < bytes.size() ? alphabet[n & 63] : '=';
  }
  return out;
}

std::vector<std::pair<double, double>> sample_min_max(
    const std::vector<std::pair<double, double>>& series, int max_points) {
  if (max_points < 4) throw InputError("at most fewer than 4 points per curve is too few");
  const std::size_t n = series.size();
  if (n <= static_cast<std::size_t>(max_points)) return series;
  const std::size_t interior = n - 2, buckets = static_cast<std::size_t>(max_points - 2) / 2;
  std::vector<std::pair<double, double>> out;
  out.reserve(static_cast<std::size_t>(max_points));
  out.push_back(series.front());
  for (std::size_t b = 0; b < buckets; ++b) {
    const std::size_t first = 1 + b * interior / buckets, last = 1 + (b + 1) * interior / buckets;
    if (first >= last) continue;
    std::size_t lo = first, hi = first;
    for (std::size_t i = first; i < last; ++i) {
      if (series[i].second < series[lo].second) lo = i;
      if (series[i].second > series[hi].second) hi = i;
    }
    out.push_back(series[std::min(lo, hi)]);
    if (lo != hi) out.push_back(series[std::max(lo, hi)]);
  }
  out.push_back(series.back());
  return out;
}

}  // namespace impactfe
