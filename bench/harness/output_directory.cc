#include "harness/output_directory.h"

#include <fcntl.h>
#include <sys/file.h>
#include <sys/stat.h>
#include <unistd.h>

#include <algorithm>
#include <cerrno>
#include <cstring>
#include <filesystem>
#include <fstream>

#include "core/csv.h"
#include "core/owned_file.h"
#include "harness/options.h"
#include "harness/record_schemas.h"
#include "harness/run_inputs.h"

namespace cb::harness {

namespace {

constexpr const char* kLockFile = ".contactbench.lock";

// The pid written in the lock file ("" if it cannot be read).
std::string HolderOf(const std::string& path) {
  std::ifstream in(path);
  std::string pid;
  in >> pid;
  return pid;
}

// Whether `fd` still is the file at `path`: a holder that releases the lock removes the file,
// and a lock taken on the removed file would lock nothing.
bool StillLinked(int fd, const std::string& path) {
  struct stat held {};
  struct stat named {};
  return ::fstat(fd, &held) == 0 && ::stat(path.c_str(), &named) == 0 &&
         held.st_dev == named.st_dev && held.st_ino == named.st_ino;
}

}  // namespace

OutputLock::OutputLock(const std::string& directory) : path_(directory + "/" + kLockFile) {
  for (;;) {
    try {
      fd_ = OpenOwnedLockFile(path_);  // never through a symbolic link (docs/hardening.md)
    } catch (const WriteError& e) {
      throw InputError("--out: the lock file: " + std::string(e.what()));
    }
    if (::flock(fd_, LOCK_EX | LOCK_NB) != 0) {
      const int error = errno;
      ::close(fd_);
      fd_ = -1;
      if (error != EWOULDBLOCK) {
        throw InputError("--out: cannot lock '" + path_ + "': " + std::strerror(error));
      }
      const std::string pid = HolderOf(path_);
      throw InputError("--out: '" + directory + "' is in use by another contactbench run (pid " +
                       (pid.empty() ? "unknown" : pid) + ")");
    }
    if (StillLinked(fd_, path_)) break;
    ::close(fd_);
  }
  const std::string pid = std::to_string(::getpid()) + "\n";
  if (::ftruncate(fd_, 0) != 0 || ::write(fd_, pid.data(), pid.size()) < 0) {
    // The pid is for the message of a refused run only; the lock holds without it.
  }
}

OutputLock::~OutputLock() {
  if (fd_ < 0) return;
  ::unlink(path_.c_str());  // while still holding the lock: see StillLinked
  ::close(fd_);
}

void ProbeWritable(const std::string& path) {
  WriteOwnedFile(path, "", FileCreation::kReplace);
  ::unlink(path.c_str());
}

std::vector<std::string> RecordsIn(const std::string& directory) {
  // figures/: `plot`'s default output, which would otherwise outlive the records it drew.
  std::vector<std::string> names = {"run.json", "vtk", kInputsDirectory, "figures"};
  for (const RecordDoc& doc : RecordDocs()) names.push_back(doc.file);
  std::vector<std::string> found;
  std::error_code ec;
  for (const std::string& name : names) {
    const std::string path = directory + "/" + name;
    if (std::filesystem::symlink_status(path, ec).type() != std::filesystem::file_type::not_found &&
        !ec) {
      if (std::find(found.begin(), found.end(), name) == found.end()) found.push_back(name);
    }
  }
  return found;
}

void ClaimOutput(const std::string& directory, bool overwrite) {
  const std::vector<std::string> records = RecordsIn(directory);
  if (records.empty()) return;
  if (!overwrite) {
    throw InputError("--out: '" + directory + "' holds the records of an earlier run (" +
                     Join(records) + "); give --overwrite to replace them, or another directory");
  }
  for (const std::string& name : records) {
    std::error_code ec;
    std::filesystem::remove_all(directory + "/" + name, ec);
    if (ec) {
      throw InputError("--overwrite: cannot remove '" + directory + "/" + name +
                       "': " + ec.message());
    }
  }
}

}  // namespace cb::harness
