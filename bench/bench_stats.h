// Small timing helpers: a wall-clock stopwatch, medians, percentiles and the worst value.
#pragma once

#include <algorithm>
#include <chrono>
#include <cmath>
#include <cstddef>
#include <vector>

namespace sap_bench {

/// Wall-clock stopwatch in milliseconds.
class Stopwatch {
 public:
  Stopwatch() : start_(std::chrono::steady_clock::now()) {}
  /// Milliseconds since construction or the last restart().
  double ms() const {
    return std::chrono::duration<double, std::milli>(std::chrono::steady_clock::now() - start_)
        .count();
  }
  void restart() { start_ = std::chrono::steady_clock::now(); }

 private:
  std::chrono::steady_clock::time_point start_;
};

/// Median of the values (mean of the two middle ones for even counts); 0 when empty.
inline double median(std::vector<double> inValues) {
  if (inValues.empty()) return 0.0;
  const std::size_t mid = inValues.size() / 2;
  std::nth_element(inValues.begin(), inValues.begin() + mid, inValues.end());
  const double upper = inValues[mid];
  if (inValues.size() % 2 == 1) return upper;
  return 0.5 * (upper + *std::max_element(inValues.begin(), inValues.begin() + mid));
}

/// The inFraction quantile of the values (nearest rank: the smallest value with at least that
/// fraction of the values at or below it); 0 when empty. percentile(v, 0.99) is the p99 frame.
inline double percentile(std::vector<double> inValues, double inFraction) {
  if (inValues.empty()) return 0.0;
  const double rank = std::ceil(inFraction * static_cast<double>(inValues.size()));
  const std::size_t index =
      std::min(inValues.size() - 1, static_cast<std::size_t>(std::max(1.0, rank)) - 1);
  std::nth_element(inValues.begin(), inValues.begin() + index, inValues.end());
  return inValues[index];
}

/// Largest value; 0 when empty.
inline double maximum(const std::vector<double>& inValues) {
  return inValues.empty() ? 0.0 : *std::max_element(inValues.begin(), inValues.end());
}

/// Arithmetic mean; 0 when empty.
inline double mean(const std::vector<double>& inValues) {
  if (inValues.empty()) return 0.0;
  double sum = 0.0;
  for (double value : inValues) sum += value;
  return sum / static_cast<double>(inValues.size());
}

}  // namespace sap_bench
