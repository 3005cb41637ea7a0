// --petsc-options that PETSc never reads (formulations/petsc/petsc_unused_options.h): refused
// after the first solve with the options named, while options PETSc reads (its own, a
// factorisation's read only when it first factors) run as before.
#include <gtest/gtest.h>
#include <unistd.h>

#include <filesystem>
#include <string>

#include "run_contactbench.h"

namespace {

#ifdef CONTACTBENCH_HAVE_PETSC

using cb::testing_support::RunContactbench;

// Each test (ctest runs them in parallel) and each process its own --out.
cb::testing_support::CliOutcome RunWith(const std::string& options) {
  const std::string test = ::testing::UnitTest::GetInstance()->current_test_info()->name();
  const auto out = std::filesystem::temp_directory_path() /
                   ("contactbench_petsc_unused_options_" + test + "_" + std::to_string(getpid()));
  std::filesystem::remove_all(out);
  const auto outcome = RunContactbench(
      "run --problem two-bar --formulation petsc-rsls --steps 3 "
      "--petsc-options '" +
      options + "' --out " + out.string());
  std::filesystem::remove_all(out);
  return outcome;
}

TEST(PetscUnusedOptionsTest, AnOptionPetscNeverReadsStopsTheRunNamingIt) {
  for (const char* option : {"-snes_monitr", "-log_view"}) {
    const auto outcome = RunWith(std::string("-snes_max_it 40 ") + option);
    EXPECT_EQ(outcome.status, 3) << outcome.output;
    EXPECT_NE(outcome.output.find("PETSc did not use " + std::string(option)), std::string::npos)
        << outcome.output;
    EXPECT_EQ(outcome.output.find("-snes_max_it"), std::string::npos) << outcome.output;
  }
}

TEST(PetscUnusedOptionsTest, OptionsPetscReadsRunAsBefore) {
  for (const char* options : {"-snes_max_it 40", "-ksp_type preonly",
                              "-pc_factor_mat_solver_type mumps -mat_mumps_icntl_14 50"}) {
    const auto outcome = RunWith(options);
    EXPECT_EQ(outcome.status, 0) << options << "\n" << outcome.output;
  }
}

#endif

}  // namespace
