// The pieces of the body in a distributed run's VTK output (docs/scale-out.md): process p's piece
// holds the elements it evaluates in the distributed step system and the nodes of those
// elements; a node shared by several pieces is owned by the lowest of their processes and marked
// a duplicate in the others, and a node of no element belongs to process 0's piece. So the
// pieces hold every element once and every node once as its owner's.
#pragma once

#include <string>
#include <vector>

#include "harness/vtk_files.h"
#include "model/elastic_body.h"

namespace cb::harness {

// Process `process`'s piece when process p evaluates the elements `parts[p]` (indices in the
// order of ElasticBody::Cells()); `parts` empty (no partition made) puts every element in
// process 0's piece. std::invalid_argument when `process` is not one of `processes`.
BodyPiece PieceOfProcess(const ElasticBody& body, const std::vector<std::vector<int>>& parts,
                         int process, int processes);

// The file of process `process`'s piece of the saved state `stem` (e.g. "block_0003").
std::string PieceFile(const std::string& stem, int process);

}  // namespace cb::harness
