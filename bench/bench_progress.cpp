// Printing progress lines.
#include "bench_progress.h"

#include <cstdio>
#include <utility>

namespace sap_bench {

Progress::Progress(std::string inTask, std::size_t inTotal)
    : task_(std::move(inTask)), total_(inTotal) {}

void Progress::step(const std::string& inDetail) {
  ++done_;
  const double now = clock_.ms();
  if (done_ < total_ && now - last_print_ms_ < 500.0) return;
  last_print_ms_ = now;
  std::fprintf(stderr, "[%s] %zu/%zu %s (%.1f s)\n", task_.c_str(), done_, total_, inDetail.c_str(),
               now / 1000.0);
}

}  // namespace sap_bench
