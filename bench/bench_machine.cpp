// Reading the machine's description.
#include "bench_machine.h"

#include <sys/utsname.h>

#include <fstream>
#include <thread>

namespace sap_bench {

std::string machineSummary() {
  utsname names{};
  const std::string host = uname(&names) == 0 ? names.nodename : "?";
  std::string model = "?";
  std::ifstream cpuinfo("/proc/cpuinfo");
  std::string line;
  while (std::getline(cpuinfo, line)) {
    if (line.rfind("model name", 0) == 0) {
      const auto colon = line.find(':');
      if (colon != std::string::npos) model = line.substr(colon + 2);
      break;
    }
  }
  return "host: " + host + ", cpu: " + model +
         ", cores: " + std::to_string(std::thread::hardware_concurrency());
}

std::string loadAverage() {
  std::ifstream file("/proc/loadavg");
  std::string one, five, fifteen;
  if (!(file >> one >> five >> fifteen)) return "?";
  return one + " " + five + " " + fifteen;
}

}  // namespace sap_bench
