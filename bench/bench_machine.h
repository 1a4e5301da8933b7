// What machine the numbers came from, and how busy it was.
#pragma once

#include <string>

namespace sap_bench {

/// "host: NAME, cpu: MODEL, cores: N" from uname and /proc/cpuinfo.
std::string machineSummary();
/// The 1-, 5- and 15-minute load averages from /proc/loadavg ("?" when unreadable).
std::string loadAverage();

}  // namespace sap_bench
