// run.json that reproduces a run and `contactbench rerun DIR --out NEW`: the machine, build,
// libraries and copied inputs recorded; a rerun's records the same as the run's (compared by
// scripts/diff_records.py, times aside); refusals with their reasons; bad DIRs.
#include <gtest/gtest.h>

#include <filesystem>
#include <fstream>
#include <iterator>
#include <nlohmann/json.hpp>
#include <string>

#include "harness/sha256.h"
#include "refusal.h"
#include "run_contactbench.h"
#include "source_tree.h"

namespace {

namespace fs = std::filesystem;
using cb::harness::Sha256Hex;
using cb::testing_support::At;
using cb::testing_support::CliOutcome;
using cb::testing_support::Names;
using cb::testing_support::Refusal;
using cb::testing_support::RefusedOption;
using cb::testing_support::RunContactbench;
using cb::testing_support::SourceRoot;

fs::path TempDir(const std::string& name) {
  auto dir = fs::temp_directory_path() / ("contactbench_rerun_" + name);
  fs::remove_all(dir);
  return dir;
}

std::string ReadBytes(const fs::path& file) {
  std::ifstream in(file, std::ios::binary);
  return {std::istreambuf_iterator<char>(in), std::istreambuf_iterator<char>()};
}

nlohmann::json RunJson(const fs::path& dir) {
  return nlohmann::json::parse(std::ifstream(dir / "run.json"));
}

void WriteJson(const fs::path& dir, const nlohmann::json& run) {
  std::ofstream(dir / "run.json") << run.dump(2);
}

// scripts/diff_records.py OLD NEW: every record the same, times aside.
CliOutcome DiffRecords(const fs::path& a, const fs::path& b) {
  return cb::testing_support::RunShell("/usr/bin/python3 " +
                                       (SourceRoot() / "scripts" / "diff_records.py").string() +
                                       " " + a.string() + " " + b.string() + " 2>&1");
}

// Reruns DIR/a into DIR/b: it must succeed and leave the same records (times aside).
void ExpectRerunReproduces(const fs::path& dir) {
  const auto o =
      RunContactbench("rerun " + (dir / "a").string() + " --out " + (dir / "b").string());
  ASSERT_EQ(o.status, 0) << o.output;
  const auto diff = DiffRecords(dir / "a", dir / "b");
  EXPECT_EQ(diff.status, 0) << diff.output;
}

// FIPS 180-4 test vectors (NIST's "SHA-256 examples"): one block, two blocks, many blocks.
TEST(Sha256Test, MatchesTheStandardsExamples) {
  EXPECT_EQ(Sha256Hex(""), "e3b0c44298fc1c149afbf4c8996fb92427ae41e4649b934ca495991b7852b855");
  EXPECT_EQ(Sha256Hex("abc"), "ba7816bf8f01cfea414140de5dae2223b00361a396177a9cb410ff61f20015ad");
  EXPECT_EQ(Sha256Hex("abcdbcdecdefdefgefghfghighijhijkijkljklmklmnlmnomnopnopq"),
            "248d6a61d20638b8e5c026930c3e6039a33ce45964ff2167f6ecedd419db06c1");
  EXPECT_EQ(Sha256Hex(std::string(1000000, 'a')),
            "cdc76e5c9914fb9281a1c7e284d73e67f1809a48a497200e046d39ccc7112cd0");
  // 55 and 56 bytes: the length fits the last block, or needs one more.
  EXPECT_NE(Sha256Hex(std::string(55, 'x')), Sha256Hex(std::string(56, 'x')));
}

TEST(RunJsonTest, RecordsTheMachineBuildLibrariesLoadAndTheProblemFilesCopies) {
  const auto dir = TempDir("fields");
  const fs::path problem = SourceRoot() / "examples" / "q4-block-gmsh.json";
  const auto o = RunContactbench("run --problem-file " + problem.string() +
                                 " --formulation implicit-fb --out " + dir.string());
  ASSERT_EQ(o.status, 0) << o.output;
  const auto run = RunJson(dir);
  EXPECT_GE(run.at("machine").at("logical_cpus").get<int>(), 1);
  EXPECT_GE(run.at("machine").at("available_cpus").get<int>(), 1);
  EXPECT_FALSE(run.at("machine").at("hostname").get<std::string>().empty());
  for (const char* when : {"start", "end"}) {
    EXPECT_GE(run.at("load_average").at(when).at("1min").get<double>(), 0.0) << when;
  }
  EXPECT_EQ(run.at("processes").get<int>(), 1);
  EXPECT_FALSE(run.at("build").at("compiler").get<std::string>().empty());
  EXPECT_EQ(run.at("build").at("binary_sha256").get<std::string>(),
            Sha256Hex(ReadBytes(CONTACTBENCH_BINARY)));
  EXPECT_FALSE(run.at("libraries").at("eigen").get<std::string>().empty());
  for (const char* library :
       {"suitesparse", "ipopt", "nlopt", "siconos-numerics", "petsc", "mpi"}) {
    EXPECT_TRUE(run.at("libraries").contains(library)) << library;
  }
  // The problem file and its Gmsh mesh, copied byte for byte with their hashes.
  const auto& inputs = run.at("inputs");
  ASSERT_EQ(inputs.size(), 2u);
  for (const auto& input : inputs) {
    const fs::path copy = dir / input.at("copy").get<std::string>();
    const fs::path source = input.at("source").get<std::string>();
    EXPECT_EQ(ReadBytes(copy), ReadBytes(source)) << copy;
    EXPECT_EQ(input.at("sha256").get<std::string>(), Sha256Hex(ReadBytes(source))) << copy;
  }
  EXPECT_EQ(inputs[1].at("copy"), "problem/q4-block-gmsh.msh");
}

TEST(RerunTest, ARerunOfARunWithAMeshReproducesItsRecords) {
  const auto dir = TempDir("mesh");
  const fs::path problem = SourceRoot() / "examples" / "q4-block-gmsh.json";
  ASSERT_EQ(
      RunContactbench("run --problem-file " + problem.string() +
                      " --formulation implicit-fb --save-every 1 --out " + (dir / "a").string())
          .status,
      0);
  ExpectRerunReproduces(dir);
  const auto rerun = RunJson(dir / "b");
  EXPECT_EQ(rerun.at("rerun_of").get<std::string>(), (dir / "a").string());
  // It read the copy, not the original.
  EXPECT_EQ(rerun.at("problem_source").get<std::string>(),
            "--problem-file " + (dir / "a" / "problem" / "q4-block-gmsh.json").string());
}

TEST(RerunTest, ARerunOfAComparisonReproducesItsRecords) {
  const auto dir = TempDir("compare");
  ASSERT_EQ(RunContactbench("compare --problem two-bar-obstacle --steps 10 --formulations "
                            "implicit-fb,active-set --starts warm,cold --repeat 2 --out " +
                            (dir / "a").string())
                .status,
            0);
  ExpectRerunReproduces(dir);
  // A changed record is seen: the comparison is not vacuous.
  std::ofstream(dir / "b" / "runs.csv", std::ios::app) << "extra,row\n";
  EXPECT_EQ(DiffRecords(dir / "a", dir / "b").status, 1);
}

TEST(RerunTest, ARerunIsRefusedWhenALibraryVersionDiffersUnlessForced) {
  const auto dir = TempDir("version");
  ASSERT_EQ(RunContactbench("run --problem bar-wall --formulation implicit-fb --out " +
                            (dir / "a").string())
                .status,
            0);
  auto run = RunJson(dir / "a");
  run["libraries"]["eigen"] = "2.0.0";
  WriteJson(dir / "a", run);
  const auto refused =
      RunContactbench("rerun " + (dir / "a").string() + " --out " + (dir / "b").string());
  EXPECT_EQ(refused.status, 2) << refused.output;
  // The run refused, and listed under it: the library, its recorded version, and the option
  // that reruns anyway.
  EXPECT_TRUE(RefusedOption(refused.output, At("rerun", {"'" + (dir / "a").string() + "'"})));
  EXPECT_TRUE(Names(refused.output, {"eigen", "2.0.0", "--force"}));
  EXPECT_FALSE(fs::exists(dir / "b" / "steps.csv"));
  const auto forced = RunContactbench("rerun " + (dir / "a").string() + " --out " +
                                      (dir / "b").string() + " --force");
  EXPECT_EQ(forced.status, 0) << forced.output;
  EXPECT_TRUE(Names(forced.output, {"eigen", "2.0.0"}));  // said, though forced
  EXPECT_EQ(DiffRecords(dir / "a", dir / "b").status, 0);
}

TEST(RerunTest, ARerunIsRefusedWhenACopiedInputChanged) {
  const auto dir = TempDir("input");
  const fs::path problem = SourceRoot() / "examples" / "truss-2d-bar-wall.json";
  ASSERT_EQ(RunContactbench("run --problem-file " + problem.string() +
                            " --formulation implicit-fb --out " + (dir / "a").string())
                .status,
            0);
  std::ofstream(dir / "a" / "problem" / "truss-2d-bar-wall.json", std::ios::app) << "\n";
  const auto refused =
      RunContactbench("rerun " + (dir / "a").string() + " --out " + (dir / "b").string());
  EXPECT_EQ(refused.status, 2) << refused.output;
  EXPECT_TRUE(RefusedOption(refused.output, At("rerun", {"'" + (dir / "a").string() + "'"})));
  EXPECT_TRUE(Names(refused.output, {"problem/truss-2d-bar-wall.json", "SHA-256"}));
}

// A mesh named outside the problem file's directory is copied by its name, and the copied
// problem file would still read the original: the rerun says so rather than pretend.
TEST(RerunTest, AMeshNamedOutsideItsProblemFilesDirectoryIsCopiedButTheRerunIsRefused) {
  const auto dir = TempDir("outside");
  fs::create_directories(dir / "problems");
  fs::copy_file(SourceRoot() / "examples" / "q4-block-gmsh.msh", dir / "block.msh");
  std::string text = ReadBytes(SourceRoot() / "examples" / "q4-block-gmsh.json");
  const std::string named = "\"q4-block-gmsh.msh\"";
  ASSERT_NE(text.find(named), std::string::npos);
  text.replace(text.find(named), named.size(), "\"../block.msh\"");
  std::ofstream(dir / "problems" / "p.json") << text;
  const auto run = RunContactbench("run --problem-file " + (dir / "problems" / "p.json").string() +
                                   " --formulation implicit-fb --out " + (dir / "a").string());
  ASSERT_EQ(run.status, 0) << run.output;
  const auto recorded = RunJson(dir / "a");
  const auto& mesh = recorded.at("inputs").at(1);
  EXPECT_EQ(mesh.at("copy"), "problem/block.msh");
  EXPECT_FALSE(mesh.at("found_by_copy").get<bool>());
  EXPECT_EQ(ReadBytes(dir / "a" / "problem" / "block.msh"), ReadBytes(dir / "block.msh"));
  const auto refused =
      RunContactbench("rerun " + (dir / "a").string() + " --out " + (dir / "b").string());
  EXPECT_EQ(refused.status, 2) << refused.output;
  // The mesh the problem file reads, outside its directory, and the copy the rerun would not.
  EXPECT_TRUE(RefusedOption(refused.output, At("rerun", {"'" + (dir / "a").string() + "'"})));
  EXPECT_TRUE(
      Names(refused.output, {"'" + (dir / "block.msh").string() + "'", "problem/block.msh"}));
}

TEST(RerunTest, ABadDirectoryIsRefusedSayingWhatIsWrong) {
  const auto dir = TempDir("bad");
  fs::create_directories(dir / "empty");
  const std::string out = " --out " + (dir / "new").string();
  // Refused at `where`, naming the directory (or what is missing) and what is wrong in it.
  auto expect_refused = [&](const std::string& args, const Refusal& expected) {
    const auto o = RunContactbench(args);
    EXPECT_EQ(o.status, 2) << args << ": " << o.output;
    EXPECT_TRUE(RefusedOption(o.output, expected)) << args;
    EXPECT_FALSE(fs::exists(dir / "new" / "run.json")) << args;
  };
  const auto quoted = [&](const char* name) {
    std::string text = (dir / name).string();  // built by insert: GCC 12's -Wrestrict misfires
    return text.insert(0, 1, '\'').append(1, '\'');  // on "'" + string + "'" here
  };
  expect_refused("rerun " + (dir / "missing").string() + out, At("rerun", {quoted("missing")}));
  std::ofstream(dir / "file") << "x";
  expect_refused("rerun " + (dir / "file").string() + out, At("rerun", {quoted("file")}));
  expect_refused("rerun " + (dir / "empty").string() + out,
                 At("rerun", {quoted("empty"), "run.json"}));
  fs::create_directories(dir / "broken");
  std::ofstream(dir / "broken" / "run.json") << "{\"command\": ";
  expect_refused("rerun " + (dir / "broken").string() + out,
                 At("rerun", {quoted("broken"), "run.json", "JSON"}));
  fs::create_directories(dir / "no_line");
  WriteJson(dir / "no_line", {{"command", "run"}});
  expect_refused("rerun " + (dir / "no_line").string() + out,
                 At("rerun", {quoted("no_line"), "\"command_line\""}));
  fs::create_directories(dir / "export");
  WriteJson(dir / "export", {{"command_line", {"contactbench", "export", "--out", "x.json"}}});
  expect_refused("rerun " + (dir / "export").string() + out,
                 At("rerun", {quoted("export"), "'export'"}));
  expect_refused("rerun" + out, At("", {"DIR"}));
  expect_refused("rerun " + (dir / "empty").string(), At("--out"));
  // Into its own directory: refused before anything is removed.
  ASSERT_EQ(RunContactbench("run --problem bar-wall --formulation implicit-fb --out " +
                            (dir / "run").string())
                .status,
            0);
  const auto same = RunContactbench("rerun " + (dir / "run").string() + " --out " +
                                    (dir / "run").string() + " --overwrite");
  EXPECT_EQ(same.status, 2) << same.output;
  EXPECT_TRUE(RefusedOption(same.output, At("--out", {"'" + (dir / "run").string() + "'"})));
  EXPECT_TRUE(fs::exists(dir / "run" / "steps.csv"));
}

}  // namespace
