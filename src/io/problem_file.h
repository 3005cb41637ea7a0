// Problem files (docs/problem-files.md): a JSON description of a truss (2-D or 3-D), a
// plane-stress Q4 mesh (nodes and elements in the file, or a Gmsh 4.1 mesh beside it), or a
// linear complementarity problem, read into the same `Problem` the named builders make, so
// every formulation runs on it; and the reverse, any Problem written as such a file.
//
// Every bad input is refused with an InputError (a std::invalid_argument) whose message names
// the file, the JSON pointer of the offending value, and the reason, e.g.
//   truss.json: /members/3/E: must be > 0, got -1
#pragma once

#include <map>
#include <string>
#include <vector>

#include "io/input_bounds.h"
#include "problems/problem.h"

namespace cb::io {

// Reads the problem file at `path`. `settings` overrides the file's run parameters by name, as
// `--set` does for named problems: length_scale, force_scale, and load (fixed-load) or
// arc_length and steps (arc-length). A mesh file is found relative to `path`'s directory. A
// file larger than `max_bytes` (input_bounds.h; 0: no bound) is refused before it is read.
Problem LoadProblemFile(const std::string& path,
                        const std::map<std::string, std::string>& settings = {},
                        std::uintmax_t max_bytes = kProblemFileMaxBytes);

// The same from the file's contents: `file` names it in messages and `directory` is where a
// referenced mesh file is looked up.
Problem ParseProblemFile(const std::string& text, const std::string& file,
                         const std::string& directory,
                         const std::map<std::string, std::string>& settings = {});

// The files a problem file's text names besides itself, as written (a Gmsh mesh's
// "mesh": {"file": F}; read relative to the problem file's directory), so that a run can keep
// copies of everything it read. Empty for text that is no JSON object.
std::vector<std::string> ReferencedFiles(const std::string& text);

// The problem as the text of a problem file which reads back to the same model (sizes, energy,
// forces, gaps, load pattern, scales, loading). Throws std::invalid_argument for a model with
// no file form (an NCP given by callbacks, a body or obstacle type the format does not have).
std::string ProblemToJson(const Problem& problem);

}  // namespace cb::io
