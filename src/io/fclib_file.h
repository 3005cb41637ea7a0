// FCLIB files (docs/problem-files.md, "FCLIB"): the contact community's HDF5 problems read as
// frictionless problems, and the suite's linear problems written as FCLIB global problems.
//
//   /fclib_local  (W, q, mu):  the LCP  0 <= r_N  _|_  W_NN r_N + q_N >= 0 on the normal
//                              components (the first of each contact's spacedim entries);
//   /fclib_global (M, H, f, w, mu): the linear body  M v = H_N r_N + f,
//                              0 <= r_N _|_ H_N^T v + w_N >= 0  (a LinearContactModel).
//
// Friction is dropped only when asked: a file with a nonzero mu is refused unless the setting
// friction=ignore is given, and the problem's notes then say what was dropped. Every bad input
// is an InputError naming the file and the HDF5 path of the offending dataset. A build without
// HDF5 refuses FCLIB files with a message saying so (FclibAvailable() is false).
#pragma once

#include <map>
#include <string>
#include <vector>

#include "core/types.h"
#include "problems/problem.h"

namespace cb::io {

// True when this build reads and writes FCLIB files (it has HDF5).
bool FclibAvailable();

// True for a path the problem-file readers treat as FCLIB: its name ends in .hdf5 or .h5.
bool IsFclibPath(const std::string& path);

// Reads the FCLIB problem at `path`. `settings` as for problem files: length_scale,
// force_scale, and friction (refuse, the default, or ignore).
Problem LoadFclibFile(const std::string& path,
                      const std::map<std::string, std::string>& settings = {});

// A state of the problem LoadFclibFile makes, in the suite's unknowns: the displacement u and
// the reactions r (r <= 0 on contact, docs/method.md (11)).
struct FclibState {
  Vec u;
  Vec r;
};

// The file's /solution (empty optional when it has none) and /guesses, as states of the problem
// LoadFclibFile(path) makes: for a local problem u = r_N and r = -u_N, for a global one u = v
// and r = -r_N.
struct FclibAnswers {
  bool has_solution = false;
  FclibState solution;
  std::vector<FclibState> guesses;
};
FclibAnswers LoadFclibAnswers(const std::string& path);

// Writes a linear problem (is_linear(), at its fixed load) as an FCLIB global problem with
// mu = 0: M = K, f = load * f, H with spacedim columns per pair (the normal, then zero
// tangential columns), w from the gaps at u = 0, spacedim the body's dimension (2 for a
// complementarity problem); `solution`, when given, as /solution, and `guess` as /guesses/1.
// Throws std::invalid_argument for a nonlinear model or a state of the wrong size.
void WriteFclibFile(const Problem& problem, const std::string& path,
                    const FclibState* solution = nullptr, const FclibState* guess = nullptr);

}  // namespace cb::io
