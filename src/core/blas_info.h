// Which BLAS the process runs on. CHOLMOD's supernodal factorisation and its solves spend their
// time in the BLAS, and on Debian the library behind libblas.so.3 is chosen by
// update-alternatives, not at build time: the same binary runs several times faster on an
// optimised BLAS than on the reference one. The benchmarks' context and run.json record it so
// that timings say what they were measured on.
#pragma once

#include <string>

namespace cb {

struct BlasInfo {
  // The file that provides dgemm_ in this process, symbolic links resolved (on Debian the
  // alternative chosen for libblas.so.3); empty when no BLAS is loaded.
  std::string library;
  // "OpenBLAS", "BLIS", "MKL" when the library identifies itself, "unidentified" otherwise
  // (the reference BLAS has no such call), "none" when no BLAS is loaded.
  std::string vendor;
  // The library's own configuration text (OpenBLAS: version, kernel, threading), or empty.
  std::string config;
  // Threads the library uses; 0 when it does not say.
  int threads = 0;
};

// Looks the BLAS up in the running process (dlsym / dladdr; it loads nothing).
BlasInfo LoadedBlas();

// One line for records and benchmark contexts: "OpenBLAS 0.3.21 ... (2 threads)
// /usr/lib/.../libblas.so.3", or "unidentified /usr/lib/.../blas/libblas.so.3", or "none".
std::string BlasDescription(const BlasInfo& blas);

// Sets the threads of an OpenBLAS or MKL in the process; false when the BLAS has no such call.
bool SetBlasThreads(int threads);

// Whether the environment chooses the BLAS's threads (OPENBLAS_NUM_THREADS, MKL_NUM_THREADS or
// OMP_NUM_THREADS set).
bool BlasThreadsChosenByEnvironment();

}  // namespace cb
