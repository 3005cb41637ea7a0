// How a distributed formulation split a body's elements over the processes of a run: one list
// per process of element indices (in the order of ElasticBody::Cells()), the same lists on every
// process. The run owns one (bench/harness/commands.cc) and hands it to its formulation
// (FormulationConfig::element_split), which records its split whenever it partitions the
// problem's body (formulations/petsc_dist/element_partition.h), and to the writers of the saved
// states (bench/harness/snapshots.h), which write each process's piece of the body from it.
#pragma once

#include <cstddef>
#include <utility>
#include <vector>

namespace cb {

class ElementSplit {
 public:
  // The split of a body of `elements` elements; replaces an earlier one.
  void Record(std::vector<std::vector<int>> elements_of_each_process, std::size_t elements) {
    parts_ = std::move(elements_of_each_process);
    elements_ = elements;
  }
  // The lists for a body of `elements` elements; empty when none was recorded for such a body
  // (one process, a serial formulation, no solve yet).
  std::vector<std::vector<int>> ElementsOfEachProcess(std::size_t elements) const {
    return elements == elements_ ? parts_ : std::vector<std::vector<int>>();
  }

 private:
  std::vector<std::vector<int>> parts_;
  std::size_t elements_ = 0;
};

}  // namespace cb
