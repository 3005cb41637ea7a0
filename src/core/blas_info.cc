#include "core/blas_info.h"

#include <dlfcn.h>

#include <cstdlib>
#include <filesystem>
#include <string>
#include <system_error>

namespace cb {

namespace {

// A function of the loaded libraries by name, or nullptr: looked up at run time so that the
// binary does not depend on any particular BLAS.
template <typename Function>
Function* Lookup(const char* name) {
  return reinterpret_cast<Function*>(dlsym(RTLD_DEFAULT, name));
}

std::string ResolvedPath(const char* path) {
  std::error_code ec;
  const std::filesystem::path resolved = std::filesystem::canonical(path, ec);
  return ec ? std::string(path) : resolved.string();
}

}  // namespace

BlasInfo LoadedBlas() {
  BlasInfo blas;
  void* dgemm = dlsym(RTLD_DEFAULT, "dgemm_");
  if (dgemm == nullptr) {
    blas.vendor = "none";
    return blas;
  }
  Dl_info where{};
  if (dladdr(dgemm, &where) != 0 && where.dli_fname != nullptr) {
    blas.library = ResolvedPath(where.dli_fname);
  }
  blas.vendor = "unidentified";
  if (auto* config = Lookup<char*()>("openblas_get_config")) {
    blas.vendor = "OpenBLAS";
    blas.config = config();
    if (auto* threads = Lookup<int()>("openblas_get_num_threads")) blas.threads = threads();
  } else if (auto* version = Lookup<const char*()>("bli_info_get_version_str")) {
    blas.vendor = "BLIS";
    blas.config = version();
  } else if (Lookup<void()>("mkl_get_version_string") != nullptr) {
    blas.vendor = "MKL";
    if (auto* threads = Lookup<int()>("mkl_get_max_threads")) blas.threads = threads();
  }
  return blas;
}

std::string BlasDescription(const BlasInfo& blas) {
  if (blas.vendor == "none") return "none";
  std::string text = blas.config.empty() ? blas.vendor : blas.config;
  if (blas.threads > 0) text += " (" + std::to_string(blas.threads) + " threads)";
  if (!blas.library.empty()) text += " " + blas.library;
  return text;
}

bool SetBlasThreads(int threads) {
  if (auto* set = Lookup<void(int)>("openblas_set_num_threads")) {
    set(threads);
    return true;
  }
  if (auto* set = Lookup<void(int)>("mkl_set_num_threads")) {
    set(threads);
    return true;
  }
  return false;
}

bool BlasThreadsChosenByEnvironment() {
  for (const char* name : {"OPENBLAS_NUM_THREADS", "MKL_NUM_THREADS", "OMP_NUM_THREADS"}) {
    if (std::getenv(name) != nullptr) return true;
  }
  return false;
}

}  // namespace cb
