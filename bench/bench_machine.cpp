// Reading the machine's description.
#include "bench_machine.h"

#include <sys/utsname.h>

#include <ctime>
#include <fstream>
#include <thread>
#include <vector>

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

std::string utcNow() {
  const std::time_t now = std::time(nullptr);
  std::tm utc{};
  gmtime_r(&now, &utc);
  char text[32];
  std::strftime(text, sizeof(text), "%Y-%m-%dT%H:%M:%SZ", &utc);
  return text;
}

void recordExperimentRun(const std::string& inDir, const std::string& inName,
                         const std::string& inConditions) {
  const std::string path = inDir + "/machine.txt";
  const std::string prefix = "experiment " + inName + ": ";
  std::vector<std::string> kept;
  std::ifstream previous(path);
  for (std::string line; std::getline(previous, line);) {
    if (line.rfind(prefix, 0) != 0) kept.push_back(line);
  }
  previous.close();
  std::ofstream file(path, std::ios::trunc);
  for (const std::string& line : kept) file << line << "\n";
  file << prefix << inConditions << "\n";
}

}  // namespace sap_bench
