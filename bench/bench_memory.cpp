// Peak memory from /proc/self/status.
#include "bench_memory.h"

#include <malloc.h>

#include <fstream>
#include <sstream>
#include <string>

namespace sap_bench {
namespace {

/// A "VmRSS"/"VmHWM" line of /proc/self/status in bytes, or 0 when unavailable.
std::size_t procStatusBytes(const std::string& inField) {
  std::ifstream status("/proc/self/status");
  std::string line;
  while (std::getline(status, line)) {
    if (line.rfind(inField + ":", 0) != 0) continue;
    std::istringstream fields(line.substr(inField.size() + 1));
    std::size_t kilobytes = 0;
    fields >> kilobytes;
    return kilobytes * 1024;
  }
  return 0;
}

}  // namespace

void PeakMeter::start() {
  malloc_trim(0);  // return freed heap so the reset peak starts from live memory
  std::ofstream clear("/proc/self/clear_refs");
  clear << "5";
  clear.flush();
  peak_reset_ = static_cast<bool>(clear);
  start_bytes_ = procStatusBytes("VmRSS");
}

std::size_t PeakMeter::grownBytes() const {
  const std::size_t peak = procStatusBytes("VmHWM");
  return peak > start_bytes_ ? peak - start_bytes_ : 0;
}

std::size_t PeakMeter::processPeakBytes() const {
  return procStatusBytes("VmHWM");
}

}  // namespace sap_bench
