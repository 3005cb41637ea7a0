#include "harness/memory_budget.h"

#include <sys/resource.h>

#include <algorithm>
#include <cmath>
#include <cstdio>
#include <cstdlib>
#include <exception>
#include <fstream>
#include <sstream>

#include "harness/options.h"

namespace cb::harness {

namespace {

constexpr double kGiB = 1024.0 * 1024.0 * 1024.0;

std::string Gib(double bytes) {
  char text[32];
  std::snprintf(text, sizeof text, "%.2f GiB", bytes / kGiB);
  return text;
}

// A number from the first line of `path` that starts with `key` (the rest of the line
// scaled by `unit`), or from the whole first line when `key` is empty.
std::optional<double> ReadNumber(const std::string& path, const std::string& key, double unit) {
  std::ifstream in(path);
  for (std::string line; std::getline(in, line);) {
    if (line.rfind(key, 0) != 0) continue;
    std::istringstream rest(line.substr(key.size()));
    double value = 0.0;
    if (rest >> value) return value * unit;
    return std::nullopt;
  }
  return std::nullopt;
}

// The memory cgroup's limit less its usage (cgroup v2, then v1); nothing when unlimited.
std::optional<double> CgroupRoom() {
  constexpr double kUnlimited = 1e18;
  for (const auto& [limit_file, usage_file] :
       {std::pair<const char*, const char*>{"/sys/fs/cgroup/memory.max",
                                            "/sys/fs/cgroup/memory.current"},
        {"/sys/fs/cgroup/memory/memory.limit_in_bytes",
         "/sys/fs/cgroup/memory/memory.usage_in_bytes"}}) {
    const auto limit = ReadNumber(limit_file, "", 1.0);  // "max" reads as nothing
    const auto usage = ReadNumber(usage_file, "", 1.0);
    if (limit && *limit < kUnlimited) return *limit - usage.value_or(0.0);
  }
  return std::nullopt;
}

// RLIMIT_AS less the process's present virtual size; nothing when unlimited.
std::optional<double> AddressSpaceRoom() {
  rlimit limit{};
  if (getrlimit(RLIMIT_AS, &limit) != 0 || limit.rlim_cur == RLIM_INFINITY) return std::nullopt;
  const auto size = ReadNumber("/proc/self/status", "VmSize:", 1024.0);
  return static_cast<double>(limit.rlim_cur) - size.value_or(0.0);
}

thread_local const char* g_activity = nullptr;

}  // namespace

double MemoryEstimate::bytes() const {
  const double work = bytes_per_unknown * dofs +
                      kBytesPerContactDofSquared * contact_dofs * contact_dofs +
                      kBytesPerFill * fill;
  return processes * kBaseBytes + (1.0 + kExtraPerProcess * (processes - 1.0)) * work;
}

std::string MemoryEstimate::Describe() const {
  std::ostringstream text;
  text << Gib(bytes()) << " (";
  if (processes > 1.0) {
    text << processes << " processes x " << kBaseBytes / (1024.0 * 1024.0) << " MiB + "
         << 1.0 + kExtraPerProcess * (processes - 1.0) << " x (";
  }
  text << static_cast<long long>(dofs) << " unknowns x " << bytes_per_unknown / 1024.0 << " KiB + "
       << static_cast<long long>(contact_dofs) << " contact dofs squared x "
       << kBytesPerContactDofSquared << " B";
  if (fill > 0.0) {
    text << " + a 3-D direct factor's fill " << std::llround(fill) << " x " << kBytesPerFill
         << " B";
  }
  if (processes > 1.0) {
    text << ")";
  } else {
    text << " + " << kBaseBytes / (1024.0 * 1024.0) << " MiB";
  }
  text << ")";
  return text.str();
}

double DirectFill3d(double dofs, double separator_nodes) {
  return dofs * std::sqrt(std::max(separator_nodes, 1.0));
}

std::optional<MemoryLimit> AvailableMemory() {
  if (const char* forced = std::getenv("CONTACTBENCH_MEMORY_LIMIT")) {
    return MemoryLimit{std::strtod(forced, nullptr), "CONTACTBENCH_MEMORY_LIMIT"};
  }
  std::optional<MemoryLimit> least;
  auto consider = [&](std::optional<double> bytes, const char* source) {
    if (bytes && (!least || *bytes < least->bytes)) least = MemoryLimit{*bytes, source};
  };
  consider(ReadNumber("/proc/meminfo", "MemAvailable:", 1024.0), "MemAvailable");
  consider(CgroupRoom(), "the memory cgroup's limit");
  consider(AddressSpaceRoom(), "RLIMIT_AS");
  return least;
}

void CheckMemory(const MemoryEstimate& estimate, const std::string& what, bool allow) {
  if (allow) return;
  const std::optional<MemoryLimit> limit = AvailableMemory();
  if (!limit || estimate.bytes() <= limit->bytes) return;
  throw InputError(what + " needs an estimated " + estimate.Describe() + ", more than the " +
                   Gib(limit->bytes) + " available (" + limit->source +
                   "); --allow-memory runs it anyway");
}

Activity::Activity(const char* doing)
    : previous_(g_activity), exceptions_(std::uncaught_exceptions()) {
  g_activity = doing;
}
Activity::~Activity() {
  if (std::uncaught_exceptions() == exceptions_) g_activity = previous_;
}
const char* Activity::Current() { return g_activity != nullptr ? g_activity : "starting"; }

}  // namespace cb::harness
