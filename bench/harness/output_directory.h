// The records of one run or comparison own their output directory: a second run into the same
// directory at the same time would splice its lines into the first one's files, and a run into
// a directory that holds an earlier run's records would overwrite some files and leave others
// (an old contacts.csv, VTK files, a runs.csv that contradicts the new records).
#pragma once

#include <string>
#include <vector>

namespace cb::harness {

// An exclusive lock on DIR (DIR/.contactbench.lock, which holds the owner's pid), held for the
// object's lifetime. Throws UsageError naming the holder's pid when another process holds it.
class OutputLock {
 public:
  explicit OutputLock(const std::string& directory);
  ~OutputLock();
  OutputLock(const OutputLock&) = delete;
  OutputLock& operator=(const OutputLock&) = delete;

 private:
  std::string path_;
  int fd_ = -1;
};

// Makes and removes the empty file `path` (a probe that the directory is writable), never
// through a symbolic link: a link of that name is refused, a regular file left by a killed run
// is replaced. Throws WriteError.
void ProbeWritable(const std::string& path);

// The record files and directories of a run found in DIR (run.json, every record file of
// docs/records.md, vtk/, and figures/ that `plot` writes there by default).
std::vector<std::string> RecordsIn(const std::string& directory);

// Refuses (UsageError) a directory that holds records, unless `overwrite`: then removes them.
void ClaimOutput(const std::string& directory, bool overwrite);

}  // namespace cb::harness
