#include "harness/machine.h"

#include <sched.h>
#include <unistd.h>

#include <cstdlib>
#include <fstream>
#include <thread>

namespace cb::harness {

namespace {

std::string CpuModel() {
  std::ifstream in("/proc/cpuinfo");
  for (std::string line; std::getline(in, line);) {
    if (line.rfind("model name", 0) != 0) continue;
    const auto colon = line.find(':');
    if (colon == std::string::npos) continue;
    const auto start = line.find_first_not_of(" \t", colon + 1);
    return start == std::string::npos ? "" : line.substr(start);
  }
  return "";
}

int AvailableCpus() {
  cpu_set_t set;
  CPU_ZERO(&set);
  if (sched_getaffinity(0, sizeof set, &set) != 0) return 0;
  return CPU_COUNT(&set);
}

}  // namespace

Machine ThisMachine() {
  Machine m;
  char name[256] = {};
  if (gethostname(name, sizeof name - 1) == 0) m.hostname = name;
  m.cpu_model = CpuModel();
  m.logical_cpus = static_cast<int>(std::thread::hardware_concurrency());
  m.available_cpus = AvailableCpus();
  return m;
}

std::array<double, 3> LoadAverage() {
  std::array<double, 3> load = {-1.0, -1.0, -1.0};
  if (getloadavg(load.data(), 3) != 3) load = {-1.0, -1.0, -1.0};
  return load;
}

}  // namespace cb::harness
