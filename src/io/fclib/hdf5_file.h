// An HDF5 file read or written through the C API with every failure a message, never HDF5's
// own error stack on stderr: the pieces the FCLIB reader and writer share. One handle owner,
// and one-dimensional datasets of ints and doubles checked for their class and size.
#pragma once

#include <hdf5.h>

#include <string>
#include <utility>
#include <vector>

namespace cb::io {

// An hid_t closed by the function that goes with its kind.
class Hdf5Handle {
 public:
  using Closer = herr_t (*)(hid_t);
  Hdf5Handle() = default;
  Hdf5Handle(hid_t id, Closer close) : id_(id), close_(close) {}
  Hdf5Handle(const Hdf5Handle&) = delete;
  Hdf5Handle& operator=(const Hdf5Handle&) = delete;
  Hdf5Handle(Hdf5Handle&& other) noexcept;
  Hdf5Handle& operator=(Hdf5Handle&& other) noexcept;
  ~Hdf5Handle();
  hid_t get() const { return id_; }
  bool valid() const { return id_ >= 0; }
  // Gives up ownership: the caller closes the id.
  hid_t release() { return std::exchange(id_, -1); }

 private:
  hid_t id_ = -1;
  Closer close_ = nullptr;
};

// An open HDF5 file; `file` names it in messages. Errors are InputError(file, path, reason).
class Hdf5File {
 public:
  // Opens an existing file for reading: refuses a missing path, a non-regular file and a file
  // that is not HDF5.
  static Hdf5File OpenForReading(const std::string& file);
  // Creates (truncates) the file at `file`.
  static Hdf5File Create(const std::string& file);

  const std::string& name() const { return name_; }
  // True when every component of `path` ("/a/b/c") exists.
  bool Has(const std::string& path) const;
  // A rank-1 (or scalar) dataset of integers or of reals: its entries, or InputError naming
  // `path` when it is missing, of another class, of another rank, or larger than `max_size`.
  std::vector<long long> Integers(const std::string& path, std::size_t max_size) const;
  std::vector<double> Reals(const std::string& path, std::size_t max_size) const;
  // The single integer at `path` (a dataset of one entry).
  long long Integer(const std::string& path) const;
  // A string dataset's text, or "" when `path` is absent or not a string.
  std::string OptionalString(const std::string& path) const;

  void MakeGroup(const std::string& path) const;
  void WriteIntegers(const std::string& path, const std::vector<int>& values) const;
  void WriteReals(const std::string& path, const double* values, std::size_t size) const;
  void WriteString(const std::string& path, const std::string& text) const;
  // Flushes and closes; InputError if HDF5 reports a failure (a full disk).
  void Close();

 private:
  Hdf5File(std::string name, hid_t id);
  [[noreturn]] void Fail(const std::string& path, const std::string& reason) const;
  Hdf5Handle OpenDataset(const std::string& path) const;
  std::size_t Extent(const Hdf5Handle& dataset, const std::string& path, std::size_t max) const;

  std::string name_;
  Hdf5Handle file_;
};

}  // namespace cb::io
