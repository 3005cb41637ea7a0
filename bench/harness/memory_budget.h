// The memory a run is allowed and the memory a problem needs, compared before the work starts
// (docs/hardening.md, "Memory"): a problem that would run out of memory is refused at once with
// the estimate (exit 2) instead of dying with std::bad_alloc after minutes of work; --allow-memory
// runs it anyway. And what the run was doing when memory ran out, for the message of a
// std::bad_alloc that gets through.
#pragma once

#include <cstdint>
#include <optional>
#include <string>

namespace cb::harness {

// The memory of a run on a model of `dofs` unknowns and `pairs` contact pairs: the sparse
// factorisations and the records grow with the unknowns, the dense contact block of the
// condensed solver (contact_block_factor.h) with the square of the contact dofs, and a direct
// factorisation of a 3-D mesh with its fill: nested dissection of a mesh whose top separator
// has s nodes fills O(dofs sqrt(s)) entries (s = n^2 on an n^3 cube: O(dofs^(4/3))), where a
// 2-D mesh's O(dofs log dofs) is within the per-unknown term. Each process of a distributed
// run holds the whole model (kExtraPerProcess); the factor is shared out among them.
struct MemoryEstimate {
  double dofs = 0.0;
  double pairs = 0.0;
  double contact_dofs = 0.0;                // the dofs the pairs act on (at most dofs)
  double fill = 0.0;                        // dofs x sqrt(s) of a direct factor in 3-D; 0 otherwise
  double processes = 1.0;                   // of a distributed run
  double bytes_per_unknown = 3.5 * 1024.0;  // kBytesPerUnknown, or an iterative solve's below
  double bytes() const;
  std::string Describe() const;  // "2.1 GiB (181202 unknowns x 3.5 KiB + ...)"
};
// Bytes per unknown, per contact dof squared and per unit of fill of MemoryEstimate::bytes()
// (measured on P1 and on hertz-3d: docs/hardening.md, "Memory").
constexpr double kBytesPerUnknown = 3.5 * 1024.0;
// A distributed iterative solve (linear=amg) holds no factor but the Jacobian twice more (its
// node-blocked copy for GAMG and the augmented split's product), GAMG's hierarchy and FGMRES's
// 2 x 100 restart vectors: more per unknown than a direct solve's non-fill part, and in 3-D
// about four times the 2-D figure (81 entries a row against 18).
constexpr double kBytesPerUnknownIterative = 6.0 * 1024.0;
constexpr double kBytesPerUnknownIterative3d = 18.0 * 1024.0;
constexpr double kBytesPerContactDofSquared = 4.0 * 8.0;
constexpr double kBytesPerFill = 420.0;
constexpr double kBaseBytes = 64.0 * 1024.0 * 1024.0;
// The work of a distributed run grows by this much per process beyond the first (the replicated
// model and vectors; two processes took 1.2-1.7 times one's memory: docs/scale-out.md).
constexpr double kExtraPerProcess = 0.5;

// The fill term of a direct factorisation of a 3-D mesh of `dofs` unknowns whose top separator
// has `separator_nodes` nodes: for a box of a x b x c nodes, the product of the two smallest;
// for an unstructured mesh of N nodes, a cube's N^(2/3).
double DirectFill3d(double dofs, double separator_nodes);

// What the process may still take: the least of MemAvailable (/proc/meminfo), the memory
// cgroup's limit less its usage, and RLIMIT_AS less the current virtual size. The variable
// CONTACTBENCH_MEMORY_LIMIT (bytes) replaces them, for tests. Nothing when none is known.
struct MemoryLimit {
  double bytes = 0.0;
  std::string source;  // "MemAvailable", "the cgroup limit", "RLIMIT_AS", ...
};
std::optional<MemoryLimit> AvailableMemory();

// Throws UsageError naming the estimate and the limit when `estimate` exceeds what is available
// (unless `allow`), `what` naming the problem.
void CheckMemory(const MemoryEstimate& estimate, const std::string& what, bool allow);

// What the run is doing, for "out of memory while <doing>": set for the extent of a scope.
class Activity {
 public:
  explicit Activity(const char* doing);
  ~Activity();
  Activity(const Activity&) = delete;
  Activity& operator=(const Activity&) = delete;
  // "starting" outside every scope. A scope left by an exception keeps its activity, so that
  // the handler of a std::bad_alloc still knows it.
  static const char* Current();

 private:
  const char* previous_;
  int exceptions_;
};

}  // namespace cb::harness
