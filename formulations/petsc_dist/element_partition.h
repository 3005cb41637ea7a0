// The partition of a body's elements and contact pairs over the processes of a distributed step
// system (docs/scale-out.md). The unknowns of a step, laid out as common/step_equations.h, are
// split into contiguous row ranges, one per process (PETSc's default layout); element e belongs
// to the process whose range holds its lowest-numbered free dof, and a contact pair to the
// process whose range holds its node's lowest free dof, as an element at that node would; an
// element or pair without a free dof goes to process 0. On a mesh numbered by a sweep (the
// problem builders' node order) each process then holds a contiguous block of elements, and the
// pairs on their nodes, whose rows it mostly owns. Written without PETSc, so that the tests check
// it in every build.
#pragma once

#include <vector>

#include "model/body_contact_model.h"
#include "model/elastic_body.h"

namespace cb {

// The process whose range holds `row`; `row_starts` has one entry per process and the total
// at the end (ascending).
int RowOwner(int row, const std::vector<int>& row_starts);

// The elements (indices in the order of ElasticBody::Cells()) of each process.
std::vector<std::vector<int>> PartitionElements(const ElasticBody& body,
                                                const std::vector<int>& row_starts);

// The pairs (indices in `pairs`, ascending) of each process.
std::vector<std::vector<int>> PartitionPairs(const ElasticBody& body,
                                             const std::vector<ContactPair>& pairs,
                                             const std::vector<int>& row_starts);

}  // namespace cb
