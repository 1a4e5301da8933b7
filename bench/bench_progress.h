// Progress of long runs on stderr (stdout keeps the tables clean).
#pragma once

#include <cstddef>
#include <string>

#include "bench_stats.h"

namespace sap_bench {

/// Counts steps of a task and prints "[task] step/total detail (elapsed)" to stderr, at most
/// about twice a second, and always for the last step.
class Progress {
 public:
  Progress(std::string inTask, std::size_t inTotal);
  /// Marks one more step done.
  void step(const std::string& inDetail = "");

 private:
  std::string task_;
  std::size_t total_;
  std::size_t done_ = 0;
  Stopwatch clock_;
  double last_print_ms_ = -1e9;
};

}  // namespace sap_bench
