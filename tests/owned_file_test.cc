// Files the suite makes are never written through a symbolic link or a hard link
// (core/owned_file.h, docs/hardening.md "Files inside --out"): a link planted in an output
// directory must leave its target as it was, and the run must say why it stopped.
#include "core/owned_file.h"

#include <fcntl.h>
#include <gtest/gtest.h>
#include <unistd.h>

#include <filesystem>
#include <fstream>
#include <iterator>
#include <string>

#include "core/csv.h"
#include "run_contactbench.h"

namespace {

namespace fs = std::filesystem;
using cb::testing_support::RunContactbench;

std::string Contents(const fs::path& path) {
  std::ifstream in(path, std::ios::binary);
  return std::string(std::istreambuf_iterator<char>(in), {});
}

// A fresh directory holding `victim`, a file outside the output directory `out`.
struct Planted {
  fs::path root, out, victim;
  explicit Planted(const std::string& name)
      : root(fs::temp_directory_path() / ("contactbench_owned_" + name)),
        out(root / "out"),
        victim(root / "victim.txt") {
    fs::remove_all(root);
    fs::create_directories(out);
    std::ofstream(victim) << "precious\n";
  }
  ~Planted() { fs::remove_all(root); }
  Planted(const Planted&) = delete;
  Planted& operator=(const Planted&) = delete;
};

TEST(OwnedFileTest, ASymbolicLinkIsRefusedAndItsTargetKept) {
  const Planted p("symlink");
  fs::create_symlink(p.victim, p.out / "steps.csv");
  for (cb::FileCreation how : {cb::FileCreation::kNew, cb::FileCreation::kReplace}) {
    try {
      cb::WriteOwnedFile((p.out / "steps.csv").string(), "x\n", how);
      FAIL() << "a symbolic link was written through";
    } catch (const cb::WriteError& e) {
      EXPECT_NE(std::string(e.what()).find("symbolic link"), std::string::npos) << e.what();
    }
  }
  EXPECT_THROW(cb::CsvWriter((p.out / "steps.csv").string(), {"a"}), cb::WriteError);
  EXPECT_THROW(cb::OpenOwnedLockFile((p.out / "steps.csv").string()), cb::WriteError);
  EXPECT_EQ(Contents(p.victim), "precious\n");
}

TEST(OwnedFileTest, AHardLinkIsReplacedNotWrittenThrough) {
  const Planted p("hardlink");
  fs::create_hard_link(p.victim, p.out / "steps.csv");
  { cb::CsvWriter csv((p.out / "steps.csv").string(), {"a", "b"}); }
  EXPECT_EQ(Contents(p.out / "steps.csv"), "a,b\n");
  EXPECT_EQ(Contents(p.victim), "precious\n");
  // A lock file must be the directory's own: a hard link to another file is refused.
  fs::create_hard_link(p.victim, p.out / ".contactbench.lock");
  EXPECT_THROW(cb::OpenOwnedLockFile((p.out / ".contactbench.lock").string()), cb::WriteError);
  EXPECT_EQ(Contents(p.victim), "precious\n");
}

TEST(OwnedFileTest, ANewFileMustNotExistAndADeviceIsOpenedAsItIs) {
  const Planted p("new");
  cb::WriteOwnedFile((p.out / "a").string(), "1", cb::FileCreation::kNew);
  EXPECT_THROW(cb::WriteOwnedFile((p.out / "a").string(), "2", cb::FileCreation::kNew),
               cb::WriteError);
  EXPECT_EQ(Contents(p.out / "a"), "1");
  // A device the caller names is neither unlinked nor refused: its write error is reported.
  EXPECT_THROW(cb::WriteOwnedFile("/dev/full", "x", cb::FileCreation::kReplace), cb::WriteError);
  EXPECT_TRUE(fs::exists("/dev/full"));
}

// The end-to-end cases of issue 30: a link named as one of the files a run makes in --out.
TEST(OwnedFileTest, ARunRefusesLinksPlantedInItsOutputDirectory) {
  for (const std::string name :
       {".contactbench.lock", ".contactbench_write_test", "steps.csv", "run.json.tmp"}) {
    const Planted p("run");
    fs::create_symlink(p.victim, p.out / name);
    const auto outcome =
        RunContactbench("run --problem two-bar --formulation implicit-fb --out " + p.out.string());
    EXPECT_EQ(Contents(p.victim), "precious\n") << name << ": " << outcome.output;
    if (name == "steps.csv") {
      // A record of an earlier run: refused (exit 2) unless --overwrite, which removes the link.
      EXPECT_EQ(outcome.status, 2) << outcome.output;
    } else if (name != "run.json.tmp") {
      EXPECT_EQ(outcome.status, 2) << name << ": " << outcome.output;
      EXPECT_NE(outcome.output.find("symbolic link"), std::string::npos) << outcome.output;
    }
    EXPECT_TRUE(fs::is_symlink(p.out / name)) << name;  // never removed to hide what happened
  }
}

}  // namespace
