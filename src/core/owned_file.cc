#include "core/owned_file.h"

#include <fcntl.h>
#include <sys/stat.h>
#include <unistd.h>

#include <cerrno>
#include <cstring>

#include "core/csv.h"

namespace cb {

namespace {

constexpr const char* kLinkRefused =
    "it is a symbolic link, and the suite never writes through one (remove it)";

// The reason of a failed open(2) with O_NOFOLLOW: ELOOP means the last component is a link.
std::string OpenFailure(const std::string& path, int error) {
  if (error == ELOOP || IsSymbolicLink(path)) return kLinkRefused;
  return std::strerror(error);
}

// Clears O_NONBLOCK (set to open a FIFO without waiting for a reader) once the file is open.
void Blocking(int fd) {
  const int flags = ::fcntl(fd, F_GETFL);
  if (flags >= 0) ::fcntl(fd, F_SETFL, flags & ~O_NONBLOCK);
}

// Opens an existing non-regular file (a device, a FIFO with a reader) as it is.
int OpenSpecial(const std::string& path) {
  const int fd = ::open(path.c_str(), O_WRONLY | O_NOFOLLOW | O_NONBLOCK | O_CLOEXEC);
  if (fd < 0) throw WriteError(path, OpenFailure(path, errno));
  Blocking(fd);
  return fd;
}

// Removes the file `fd` opened at `path` when it is a regular file (never a device it named).
void RemoveIfRegular(int fd, const std::string& path) {
  struct stat status {};
  if (::fstat(fd, &status) == 0 && S_ISREG(status.st_mode)) ::unlink(path.c_str());
}

}  // namespace

bool IsSymbolicLink(const std::string& path) {
  struct stat status {};
  return ::lstat(path.c_str(), &status) == 0 && S_ISLNK(status.st_mode);
}

int OpenOwnedFile(const std::string& path, FileCreation how) {
  if (how == FileCreation::kReplace) {
    struct stat status {};
    if (::lstat(path.c_str(), &status) == 0) {
      if (S_ISLNK(status.st_mode)) throw WriteError(path, kLinkRefused);
      if (!S_ISREG(status.st_mode) && !S_ISDIR(status.st_mode)) return OpenSpecial(path);
      // Unlinking removes the name only: the file a hard link shares is left as it was.
      if (S_ISREG(status.st_mode) && ::unlink(path.c_str()) != 0 && errno != ENOENT) {
        throw WriteError(path, std::string("cannot replace it: ") + std::strerror(errno));
      }
    }
  }
  const int fd = ::open(path.c_str(), O_WRONLY | O_CREAT | O_EXCL | O_NOFOLLOW | O_CLOEXEC, 0644);
  if (fd < 0) {
    const int error = errno;
    throw WriteError(path, error == EEXIST && !IsSymbolicLink(path)
                               ? "it already exists (made by another process?)"
                               : OpenFailure(path, error));
  }
  return fd;
}

int OpenOwnedLockFile(const std::string& path) {
  const int fd = ::open(path.c_str(), O_RDWR | O_CREAT | O_NOFOLLOW | O_NONBLOCK | O_CLOEXEC, 0644);
  if (fd < 0) throw WriteError(path, OpenFailure(path, errno));
  struct stat status {};
  if (::fstat(fd, &status) != 0 || !S_ISREG(status.st_mode) || status.st_nlink != 1) {
    ::close(fd);
    throw WriteError(path, "it is not a regular file of one link (remove it)");
  }
  Blocking(fd);
  return fd;
}

void WriteAll(int fd, std::string_view bytes, const std::string& path) {
  std::size_t written = 0;
  while (written < bytes.size()) {
    const ssize_t n = ::write(fd, bytes.data() + written, bytes.size() - written);
    if (n > 0) {
      written += static_cast<std::size_t>(n);
    } else if (n < 0 && errno == EINTR) {
      continue;
    } else {
      throw WriteError(path, n < 0 ? std::strerror(errno) : "short write");
    }
  }
}

void WriteOwnedFile(const std::string& path, std::string_view bytes, FileCreation how) {
  const int fd = OpenOwnedFile(path, how);
  try {
    WriteAll(fd, bytes, path);
  } catch (const WriteError&) {
    RemoveIfRegular(fd, path);
    ::close(fd);
    throw;
  }
  if (::close(fd) != 0) throw WriteError(path, std::strerror(errno));
}

}  // namespace cb
