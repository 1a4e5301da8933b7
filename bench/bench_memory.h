// Peak resident memory of a stretch of work, read from /proc/self/status (Linux).
#pragma once

#include <cstddef>

namespace sap_bench {

/// Measures how far the process's peak resident set rises above the resident set at start():
/// the heap is trimmed and the peak (VmHWM) reset through /proc/self/clear_refs, so the growth
/// is the work's own buffers.
class PeakMeter {
 public:
  /// Trims the heap, resets the peak and remembers the current resident set.
  void start();
  /// Bytes the peak rose above the start (0 when /proc is unavailable).
  std::size_t grownBytes() const;
  /// The process's peak resident set in bytes.
  std::size_t processPeakBytes() const;
  /// Whether start() could reset the peak (Linux >= 4.0); else the growth is an upper bound.
  bool peakReset() const { return peak_reset_; }

 private:
  std::size_t start_bytes_ = 0;
  bool peak_reset_ = false;
};

}  // namespace sap_bench
