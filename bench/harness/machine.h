// The machine a run ran on, as run.json records it: what decides its times (the CPU, the cores
// this process may use, how loaded the machine was) and where it ran.
#pragma once

#include <array>
#include <string>

namespace cb::harness {

struct Machine {
  std::string hostname;
  std::string cpu_model;   // /proc/cpuinfo's "model name" ("" when unknown)
  int logical_cpus = 0;    // online logical CPUs
  int available_cpus = 0;  // of those, the ones this process may run on (its affinity)
};

Machine ThisMachine();

// The load average over 1, 5 and 15 minutes (getloadavg); -1 each when unknown.
std::array<double, 3> LoadAverage();

}  // namespace cb::harness
