// What machine the numbers came from, and how busy it was.
#pragma once

#include <string>

namespace sap_bench {

/// "host: NAME, cpu: MODEL, cores: N" from uname and /proc/cpuinfo.
std::string machineSummary();
/// The 1-, 5- and 15-minute load averages from /proc/loadavg ("?" when unreadable).
std::string loadAverage();
/// The current UTC time as "YYYY-MM-DDTHH:MM:SSZ".
std::string utcNow();

/// Records in DIR/machine.txt under what conditions experiment inName ran: its line
/// "experiment NAME: inConditions" replaces the one of its last run, so the file describes
/// the results beside it; other lines (the machine's description) are kept.
void recordExperimentRun(const std::string& inDir, const std::string& inName,
                         const std::string& inConditions);

}  // namespace sap_bench
