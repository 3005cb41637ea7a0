#include "core/blas_info.h"

#include <gtest/gtest.h>

#include <filesystem>

namespace cb {
namespace {

// The test binary links CHOLMOD, hence a BLAS: it must be found, by the file it lives in.
TEST(BlasInfo, FindsTheLoadedBlasAndItsFile) {
  const BlasInfo blas = LoadedBlas();
  EXPECT_NE(blas.vendor, "none");
  ASSERT_FALSE(blas.library.empty());
  EXPECT_TRUE(std::filesystem::exists(blas.library)) << blas.library;
  EXPECT_FALSE(std::filesystem::is_symlink(blas.library)) << "links are resolved";
  // OpenBLAS identifies itself; its Debian alternative lives under openblas*/.
  if (blas.library.find("openblas") != std::string::npos) {
    EXPECT_EQ(blas.vendor, "OpenBLAS");
    EXPECT_EQ(blas.config.rfind("OpenBLAS", 0), 0u) << blas.config;
  }
}

TEST(BlasInfo, DescriptionNamesConfigurationThreadsAndFile) {
  BlasInfo blas;
  blas.vendor = "OpenBLAS";
  blas.config = "OpenBLAS 0.3.21 Haswell";
  blas.threads = 2;
  blas.library = "/lib/libblas.so.3";
  EXPECT_EQ(BlasDescription(blas), "OpenBLAS 0.3.21 Haswell (2 threads) /lib/libblas.so.3");
  blas = BlasInfo{};
  blas.vendor = "unidentified";
  blas.library = "/lib/blas/libblas.so.3";
  EXPECT_EQ(BlasDescription(blas), "unidentified /lib/blas/libblas.so.3");
  blas = BlasInfo{};
  blas.vendor = "none";
  EXPECT_EQ(BlasDescription(blas), "none");
}

// Setting the threads is seen by the next look-up, where the BLAS has the call (OpenBLAS here).
TEST(BlasInfo, SetThreadsIsWhatTheLibraryThenReports) {
  const BlasInfo before = LoadedBlas();
  if (before.vendor != "OpenBLAS") GTEST_SKIP() << "needs OpenBLAS, not " << before.vendor;
  ASSERT_TRUE(SetBlasThreads(1));
  EXPECT_EQ(LoadedBlas().threads, 1);
  ASSERT_TRUE(SetBlasThreads(before.threads));
  EXPECT_EQ(LoadedBlas().threads, before.threads);
}

}  // namespace
}  // namespace cb
