// The files the suite makes (record files, run.json, VTK, the lock and the write probe of an
// output directory) are opened here and only here, never through a symbolic link: anyone who
// can create entries in an output directory (a directory under /tmp, say) could otherwise make
// a run truncate or overwrite the file a link points to, with the run's privileges
// (docs/hardening.md, "Files inside --out").
#pragma once

#include <string>
#include <string_view>

namespace cb {

enum class FileCreation {
  kNew,      // the file must not exist (O_EXCL): a probe, a temporary file
  kReplace,  // an existing regular file is unlinked first, then made anew (O_EXCL), so that a
             // hard link to another file is never written through; a device or FIFO the
             // caller names (/dev/full, /dev/null) is opened as it is, without blocking
};

// Opens `path` for writing as `how` says, with O_NOFOLLOW and O_CLOEXEC. Throws WriteError
// naming the path; a symbolic link is refused with a sentence that says so.
int OpenOwnedFile(const std::string& path, FileCreation how);

// Opens (creating) the lock file `path` for reading and writing without truncating it: it must
// be a regular file with a single link, reached without a symbolic link. Throws WriteError.
int OpenOwnedLockFile(const std::string& path);

// Writes all of `bytes` to `fd` (retrying short writes and EINTR). Throws WriteError naming
// `path` with the system's reason.
void WriteAll(int fd, std::string_view bytes, const std::string& path);

// Writes `bytes` as the whole of the file `path` (OpenOwnedFile, WriteAll, close). A file cut
// short is removed before WriteError is thrown.
void WriteOwnedFile(const std::string& path, std::string_view bytes, FileCreation how);

// Whether `path` itself (not what it points to) is a symbolic link.
bool IsSymbolicLink(const std::string& path);

}  // namespace cb
