// FCLIB files (src/io/fclib_file.h): the five Siconos test files read as frictionless problems
// and solved under the verdict; the suite's problems written and read back to the same model
// and the same answer; FCLIB's own reader (libfclib, when the build found it) reading what the
// suite writes; bad files refused with the file, the HDF5 path and the reason.
#include <gtest/gtest.h>

#include <filesystem>
#include <fstream>
#include <nlohmann/json.hpp>
#include <string>

#include "formulations/registry.h"
#include "io/fclib_file.h"
#include "io/input_error.h"
#include "io/problem_file.h"
#include "model/linear_contact_model.h"
#include "path/path.h"
#include "problems/problem.h"
#include "record_table.h"
#include "refusal.h"
#include "run_contactbench.h"
#include "source_tree.h"
#include "verdict/verdict.h"

#ifdef CONTACTBENCH_HAVE_FCLIB_LIBRARY
extern "C" {  // fclib.h declares C functions without a C++ guard
#include <fclib.h>
}
#endif

namespace cb {
namespace {

using ::cb::testing_support::At;
using ::cb::testing_support::CliOutcome;
using ::cb::testing_support::Names;
using ::cb::testing_support::RefusalLine;
using ::cb::testing_support::RefusedAt;
using ::cb::testing_support::RunContactbench;

const std::filesystem::path kData = ::cb::testing_support::SourceRoot() / "tests/data/fclib";

std::filesystem::path TempDir(const std::string& name) {
  auto dir = std::filesystem::temp_directory_path() / ("contactbench_fclib_" + name);
  std::filesystem::remove_all(dir);
  std::filesystem::create_directories(dir);
  return dir;
}

StepProblem FixedLoadStep(const Problem& p) {
  return StepProblem{p.model.get(), ZeroState(*p.model), StepConstraint::FixedLoad(p.load),
                     p.scales};
}

// From u = 0, r = 0, as `run` starts a fixed-load step. A time limit: NLopt's first-order
// methods crawl on some of these problems (a formulation's failure, which the verdict reports).
StepResult SolveWith(const std::string& formulation, const StepProblem& step) {
  const auto f = MakeFormulation(formulation, FormulationConfig());
  StartPoint start;
  start.du = Vec::Zero(step.model->num_dofs());
  start.r = Vec::Zero(step.model->num_pairs());
  SolveControls controls;
  controls.time_limit_s = 5.0;
  return f->Solve(step, start, controls);
}

std::string ExpectMessage(const std::function<void()>& load) {
  try {
    load();
  } catch (const io::InputError& e) {
    return e.what();
  }
  ADD_FAILURE() << "not refused";
  return "";
}

struct FileCase {
  const char* file;
  bool global;
  int dofs;   // global: M's size; local: the contacts (the LCP's size)
  int pairs;  // contacts
};

// Sizes as the files state them (m, n of M and H, or W, over spacedim 3).
const FileCase kFiles[] = {
    {"Box_Stacks-i0122-82-5.hdf5", true, 450, 82},
    {"Capsules-i125-1213.hdf5", false, 286, 286},
    {"CubeH8.hdf5", true, 162, 1},
    {"LMGC_100_PR_PerioBox-i00361-60-03000.hdf5", false, 60, 60},
    {"LMGC_GlobalFrictionContactProblem00046.hdf5", true, 162, 9},
};

class FclibFiles : public ::testing::TestWithParam<FileCase> {
 protected:
  void SetUp() override {
    if (!io::FclibAvailable()) GTEST_SKIP() << "built without HDF5";
  }
};

TEST_P(FclibFiles, FrictionIsRefusedUnlessDroppedAndThenNoted) {
  const std::string path = (kData / GetParam().file).string();
  const std::string message = ExpectMessage([&] { io::LoadProblemFile(path); });
  // The file, the dataset of the friction and the setting that drops it.
  EXPECT_TRUE(RefusedAt(message, path, At("", {"/vectors/mu", "friction=ignore"})));

  const Problem p = io::LoadProblemFile(path, {{"friction", "ignore"}});
  EXPECT_EQ(p.model->num_dofs(), GetParam().dofs);
  EXPECT_EQ(p.model->num_pairs(), GetParam().pairs);
  ASSERT_FALSE(p.notes.empty());
  EXPECT_TRUE(Names(p.notes.back(), {"friction", "mu = 0"}));
  EXPECT_TRUE(Names(p.description, {p.notes.back()}));
}

// Every formulation that accepts the problem runs on it; the verdict judges. implicit-fb is
// verified on all five; a global problem's M is positive definite, so its answer u is unique
// and every verified formulation finds the same one.
TEST_P(FclibFiles, SolvedAndJudgedByEveryFormulationThatAcceptsIt) {
  const Problem p =
      io::LoadProblemFile((kData / GetParam().file).string(), {{"friction", "ignore"}});
  const StepProblem step = FixedLoadStep(p);
  const StepResult reference = SolveWith("implicit-fb", step);
  const Verdict judged = Judge(step, reference.point, 1e-8);
  ASSERT_TRUE(judged.verified) << reference.message << " eq_res " << judged.eq_res << " comp_res "
                               << judged.comp_res;
  const double size = std::max(reference.point.du.lpNorm<Eigen::Infinity>(), 1e-300);
  int verified = 0;
  for (const FormulationInfo& info : FormulationRegistry()) {
    if (!info.available || info.distributed) continue;
    const auto formulation = MakeFormulation(info.name, FormulationConfig());
    if (!formulation->Accepts(step, nullptr)) continue;
    const StepResult result = SolveWith(info.name, step);
    const Verdict verdict = Judge(step, result.point, 1e-8);
    if (!verdict.verified) continue;  // a failure is the formulation's, reported by the verdict
    ++verified;
    if (GetParam().global) {
      EXPECT_LE((result.point.du - reference.point.du).lpNorm<Eigen::Infinity>(), 1e-5 * size)
          << info.name;
    }
  }
  EXPECT_GE(verified, 2);
}

INSTANTIATE_TEST_SUITE_P(Siconos, FclibFiles, ::testing::ValuesIn(kFiles),
                         [](const ::testing::TestParamInfo<FileCase>& info) {
                           std::string name = info.param.file;
                           name = name.substr(0, name.find('.'));
                           for (char& c : name) {
                             if (!std::isalnum(static_cast<unsigned char>(c))) c = '_';
                           }
                           return name;
                         });

class FclibRoundTrip : public ::testing::Test {
 protected:
  void SetUp() override {
    if (!io::FclibAvailable()) GTEST_SKIP() << "built without HDF5";
  }
};

// P1 written with its verified answer, read back: the same K, f, gaps and normals (FCLIB's M
// and H are the suite's matrices as written, in binary64), the file's /solution is the answer
// written, and solving the read-back problem gives the same answer to 1e-12.
TEST_F(FclibRoundTrip, BlockWrittenAndReadBackGivesTheSameAnswer) {
  const Problem block = MakeProblem("block", {{"n", "6"}});
  const StepProblem step = FixedLoadStep(block);
  const StepResult solved = SolveWith("implicit-fb", step);
  ASSERT_TRUE(Judge(step, solved.point, 1e-8).verified) << solved.message;

  const auto path = (TempDir("block") / "block.hdf5").string();
  const io::FclibState answer{solved.point.du, solved.point.r};
  const io::FclibState guess{Vec::Zero(block.model->num_dofs()),
                             Vec::Zero(block.model->num_pairs())};
  io::WriteFclibFile(block, path, &answer, &guess);
  const Problem back = io::LoadProblemFile(path);
  EXPECT_TRUE(back.notes.empty());  // mu = 0 and M exactly symmetric: nothing changed

  const Vec u = solved.point.du;
  Vec k_u, k_u_back, phi, phi_back;
  block.model->InternalForce(u, &k_u);
  back.model->InternalForce(u, &k_u_back);
  // block's grad pi(0) = 0, so f_file = f and the equilibrium residuals agree term by term.
  EXPECT_LE((k_u - k_u_back).lpNorm<Eigen::Infinity>(), 1e-14 * k_u.lpNorm<Eigen::Infinity>());
  EXPECT_EQ((block.load * block.model->load_pattern() - back.model->load_pattern()).norm(), 0.0);
  block.model->Gaps(u, &phi);
  back.model->Gaps(u, &phi_back);
  EXPECT_LE((phi - phi_back).lpNorm<Eigen::Infinity>(),
            1e-15 * (1.0 + phi.lpNorm<Eigen::Infinity>()));

  const io::FclibAnswers answers = io::LoadFclibAnswers(path);
  ASSERT_TRUE(answers.has_solution);
  EXPECT_EQ(answers.solution.u, answer.u);
  EXPECT_EQ(answers.solution.r, answer.r);
  ASSERT_EQ(answers.guesses.size(), 1u);
  EXPECT_EQ(answers.guesses[0].u, guess.u);

  // The answer written is an answer of the problem read back, under the verdict.
  const StepProblem back_step = FixedLoadStep(back);
  StepPoint written;
  written.du = answers.solution.u;
  written.r = answers.solution.r;
  written.dlambda = back.load;
  EXPECT_TRUE(Judge(back_step, written, 1e-8).verified);

  // Solved again from the file (its own data scales, not the named problem's): the same u.
  const StepResult again = SolveWith("active-set", back_step);
  ASSERT_TRUE(Judge(back_step, again.point, 1e-8).verified) << again.message;
  const StepResult first = SolveWith("active-set", step);
  EXPECT_LE((again.point.du - first.point.du).lpNorm<Eigen::Infinity>(),
            1e-12 * first.point.du.lpNorm<Eigen::Infinity>());
  EXPECT_LE((again.point.r - first.point.r).lpNorm<Eigen::Infinity>(),
            1e-12 * first.point.r.lpNorm<Eigen::Infinity>());
}

TEST_F(FclibRoundTrip, NonlinearOrEnergylessProblemsAreNotWritten) {
  const auto dir = TempDir("refused");
  const Problem arch = MakeProblem("arch-flat");
  EXPECT_THROW(io::WriteFclibFile(arch, (dir / "a.hdf5").string()), std::invalid_argument);
  EXPECT_FALSE(std::filesystem::exists(dir / "a.hdf5"));
}

TEST_F(FclibRoundTrip, BadFilesAreRefusedWithFileAndReason) {
  const auto dir = TempDir("bad");
  const std::string text = (dir / "text.hdf5").string();
  std::ofstream(text) << "not hdf5";
  EXPECT_TRUE(RefusedAt(ExpectMessage([&] { io::LoadProblemFile(text); }), text,
                        At("", {"HDF5"})));  // what the file is not
  const std::string missing = (dir / "missing.h5").string();
  EXPECT_TRUE(RefusedAt(ExpectMessage([&] { io::LoadProblemFile(missing); }), missing, At("")));
  // A good file with a bad setting.
  const std::string good = (dir / "good.hdf5").string();
  const Problem block = MakeProblem("block", {{"n", "2"}});
  io::WriteFclibFile(block, good);
  const std::string unknown = ExpectMessage([&] {
    io::LoadProblemFile(good, {{"friction", "sometimes"}});
  });
  // The setting, its bad value and the valid ones.
  EXPECT_TRUE(RefusedAt(unknown, good, At("", {"friction", "'sometimes'", "refuse", "ignore"})));
}

// Through the CLI: a frictional file refused (exit 2, the dataset named), the same file with
// friction=ignore run and run.json saying what was dropped; an exported P1 runs and verifies.
TEST_F(FclibRoundTrip, TheCliRefusesFrictionAndRecordsItsDrop) {
  const auto dir = TempDir("cli");
  const std::string file = (kData / "CubeH8.hdf5").string();
  const CliOutcome refused =
      RunContactbench("run --problem-file " + file + " --formulation active-set --out " +
                      (dir / "refused").string());
  EXPECT_EQ(refused.status, 2) << refused.output;
  EXPECT_TRUE(
      RefusedAt(RefusalLine(refused.output), file, At("/fclib_global/vectors/mu", {"friction"})));
  EXPECT_FALSE(std::filesystem::exists(dir / "refused" / "steps.csv"));

  const CliOutcome run = RunContactbench("run --problem-file " + file +
                                         " --set friction=ignore --formulation active-set --out " +
                                         (dir / "run").string());
  ASSERT_EQ(run.status, 0) << run.output;
  std::ifstream in(dir / "run" / "run.json");
  const nlohmann::json record = nlohmann::json::parse(in);
  const auto& notes = record.at("problem_notes");
  ASSERT_EQ(notes.size(), 2u) << notes.dump();
  // The two changes made to the file's problem, in the order made: M symmetrised, then the
  // friction of its one contact dropped.
  EXPECT_TRUE(Names(notes[0].get<std::string>(), {"M^T"}));
  EXPECT_TRUE(Names(notes[1].get<std::string>(), {"friction", "1 of 1", "mu = 0"}));
  EXPECT_EQ(record.at("settings").at("friction"), "ignore");

  const std::string exported = (dir / "block.hdf5").string();
  const CliOutcome written = RunContactbench(
      "export --problem block --set n=3 --format fclib "
      "--out " +
      exported);
  ASSERT_EQ(written.status, 0) << written.output;
  const CliOutcome solved =
      RunContactbench("run --problem-file " + exported + " --formulation implicit-fb --out " +
                      (dir / "block").string());
  EXPECT_EQ(solved.status, 0) << solved.output;
  const auto steps = ::cb::testing_support::Table(dir / "block" / "steps.csv");
  ASSERT_EQ(steps.size(), 1u);
  EXPECT_EQ(steps[0].at("verified"), "true");
}

#ifdef CONTACTBENCH_HAVE_FCLIB_LIBRARY
// FCLIB's own reader (libfclib, not the suite's) reads an exported P1: the same sizes, the
// spacedim, mu = 0, and M, f as the suite's stiffness and load.
TEST_F(FclibRoundTrip, FclibsOwnReaderReadsWhatTheSuiteWrites) {
  const Problem block = MakeProblem("block", {{"n", "4"}});
  const auto path = (TempDir("interop") / "block.hdf5").string();
  io::WriteFclibFile(block, path);
  fclib_global* g = fclib_read_global(path.c_str());
  ASSERT_NE(g, nullptr);
  const int n = block.model->num_dofs();
  EXPECT_EQ(g->spacedim, 2);
  EXPECT_EQ(g->M->m, n);
  EXPECT_EQ(g->M->n, n);
  EXPECT_EQ(g->M->nz, -1);
  EXPECT_EQ(g->H->n, 2 * block.model->num_pairs());
  EXPECT_EQ(g->G, nullptr);
  SpMat k;
  block.model->Stiffness(Vec::Zero(n), &k);
  const Eigen::Map<const SpMat> m(n, n, g->M->nzmax, g->M->p, g->M->i, g->M->x);
  EXPECT_EQ((SpMat(m) - k).norm(), 0.0);
  for (int p = 0; p < block.model->num_pairs(); ++p) EXPECT_EQ(g->mu[p], 0.0);
  for (int i = 0; i < n; ++i) EXPECT_EQ(g->f[i], block.load * block.model->load_pattern()(i));
  fclib_delete_global(g);
  free(g);
}
#ifdef CONTACTBENCH_HAVE_SICONOS
// Interop: P1 exported, read by FCLIB's own reader (not the suite's), its M, H, f, w handed to
// Siconos' Lemke solver (siconos-lemke: the LCP of the normal columns with v eliminated); it
// reaches the answer the suite's implicit-fb finds on the named problem.
TEST_F(FclibRoundTrip, SiconosSolvesWhatFclibsReaderReadsToTheSuitesAnswer) {
  const Problem block = MakeProblem("block", {{"n", "4"}});
  const StepProblem step = FixedLoadStep(block);
  const StepResult suite = SolveWith("implicit-fb", step);
  ASSERT_TRUE(Judge(step, suite.point, 1e-8).verified) << suite.message;
  const auto path = (TempDir("siconos") / "block.hdf5").string();
  io::WriteFclibFile(block, path);

  fclib_global* g = fclib_read_global(path.c_str());
  ASSERT_NE(g, nullptr);
  ASSERT_EQ(g->M->nz, -1);  // compressed columns, as written
  ASSERT_EQ(g->H->nz, -1);
  const int n = g->M->n, d = g->spacedim, nc = g->H->n / d;
  const SpMat m = Eigen::Map<const SpMat>(n, n, g->M->nzmax, g->M->p, g->M->i, g->M->x);
  const SpMat h = Eigen::Map<const SpMat>(n, g->H->n, g->H->nzmax, g->H->p, g->H->i, g->H->x);
  std::vector<Triplet> pick;
  for (int p = 0; p < nc; ++p) pick.emplace_back(p * d, p, 1.0);
  SpMat select(g->H->n, nc);
  select.setFromTriplets(pick.begin(), pick.end());
  const Vec w = Eigen::Map<const Vec>(g->w, g->H->n);
  const Vec f = Eigen::Map<const Vec>(g->f, n);
  const LinearContactModel model(m, h * select, SpMat(select.transpose()) * w, f);
  fclib_delete_global(g);
  free(g);

  const StepProblem from_fclib{&model, ZeroState(model), StepConstraint::FixedLoad(1.0),
                               block.scales};
  const StepResult siconos = SolveWith("siconos-lemke", from_fclib);
  ASSERT_TRUE(Judge(from_fclib, siconos.point, 1e-8).verified) << siconos.message;
  EXPECT_LE((siconos.point.du - suite.point.du).lpNorm<Eigen::Infinity>(),
            1e-8 * suite.point.du.lpNorm<Eigen::Infinity>());
  EXPECT_LE((siconos.point.r - suite.point.r).lpNorm<Eigen::Infinity>(),
            1e-8 * suite.point.r.lpNorm<Eigen::Infinity>());
}
#endif
#endif

}  // namespace
}  // namespace cb
