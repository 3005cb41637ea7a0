#include "io/fclib/hdf5_file.h"

#include <filesystem>
#include <utility>

#include "io/input_error.h"

namespace cb::io {

namespace {

// HDF5 prints its error stack to stderr by default; every failure here is reported as an
// InputError instead, so the stack is switched off once for the process.
void SilenceHdf5Errors() {
  static const bool silenced = [] {
    H5Eset_auto2(H5E_DEFAULT, nullptr, nullptr);
    return true;
  }();
  (void)silenced;
}

}  // namespace

Hdf5Handle::Hdf5Handle(Hdf5Handle&& other) noexcept
    : id_(std::exchange(other.id_, -1)), close_(other.close_) {}

Hdf5Handle& Hdf5Handle::operator=(Hdf5Handle&& other) noexcept {
  if (this != &other) {
    if (id_ >= 0 && close_ != nullptr) close_(id_);
    id_ = std::exchange(other.id_, -1);
    close_ = other.close_;
  }
  return *this;
}

Hdf5Handle::~Hdf5Handle() {
  if (id_ >= 0 && close_ != nullptr) close_(id_);
}

Hdf5File::Hdf5File(std::string name, hid_t id) : name_(std::move(name)), file_(id, H5Fclose) {}

void Hdf5File::Fail(const std::string& path, const std::string& reason) const {
  throw InputError(name_, path, reason);
}

Hdf5File Hdf5File::OpenForReading(const std::string& file) {
  SilenceHdf5Errors();
  std::error_code ec;
  const auto status = std::filesystem::status(file, ec);
  if (!std::filesystem::exists(status)) throw InputError(file, "", "no such FCLIB file");
  if (!std::filesystem::is_regular_file(status)) {
    throw InputError(file, "", "not a regular file (an FCLIB file is an HDF5 file)");
  }
  if (H5Fis_hdf5(file.c_str()) <= 0) {
    throw InputError(file, "", "not an HDF5 file (an FCLIB file is HDF5)");
  }
  const hid_t id = H5Fopen(file.c_str(), H5F_ACC_RDONLY, H5P_DEFAULT);
  if (id < 0) throw InputError(file, "", "HDF5 cannot open it");
  return Hdf5File(file, id);
}

Hdf5File Hdf5File::Create(const std::string& file) {
  SilenceHdf5Errors();
  const hid_t id = H5Fcreate(file.c_str(), H5F_ACC_TRUNC, H5P_DEFAULT, H5P_DEFAULT);
  if (id < 0) throw InputError(file, "", "cannot create the HDF5 file");
  return Hdf5File(file, id);
}

bool Hdf5File::Has(const std::string& path) const {
  // H5Lexists fails (not false) when an intermediate group is missing: test each prefix.
  std::size_t start = 1;
  while (start <= path.size()) {
    const std::size_t slash = path.find('/', start);
    const std::string prefix = path.substr(0, slash);
    if (H5Lexists(file_.get(), prefix.c_str(), H5P_DEFAULT) <= 0) return false;
    if (slash == std::string::npos) break;
    start = slash + 1;
  }
  return true;
}

Hdf5Handle Hdf5File::OpenDataset(const std::string& path) const {
  if (!Has(path)) Fail(path, "missing");
  Hdf5Handle dataset(H5Dopen2(file_.get(), path.c_str(), H5P_DEFAULT), H5Dclose);
  if (!dataset.valid()) Fail(path, "not a dataset HDF5 can open (a group?)");
  return dataset;
}

std::size_t Hdf5File::Extent(const Hdf5Handle& dataset, const std::string& path,
                             std::size_t max) const {
  Hdf5Handle space(H5Dget_space(dataset.get()), H5Sclose);
  if (!space.valid()) Fail(path, "HDF5 cannot read the dataset's shape");
  const int rank = H5Sget_simple_extent_ndims(space.get());
  if (rank == 0) return 1;  // a scalar
  if (rank != 1) Fail(path, "must be one-dimensional, has rank " + std::to_string(rank));
  hsize_t size = 0;
  H5Sget_simple_extent_dims(space.get(), &size, nullptr);
  if (size > max) {
    Fail(path, "has " + std::to_string(size) + " entries, more than the " + std::to_string(max) +
                   " the problem's sizes allow");
  }
  return static_cast<std::size_t>(size);
}

std::vector<long long> Hdf5File::Integers(const std::string& path, std::size_t max_size) const {
  const Hdf5Handle dataset = OpenDataset(path);
  Hdf5Handle type(H5Dget_type(dataset.get()), H5Tclose);
  if (H5Tget_class(type.get()) != H5T_INTEGER) Fail(path, "must hold integers");
  std::vector<long long> values(Extent(dataset, path, max_size));
  if (!values.empty() &&
      H5Dread(dataset.get(), H5T_NATIVE_LLONG, H5S_ALL, H5S_ALL, H5P_DEFAULT, values.data()) < 0) {
    Fail(path, "HDF5 cannot read the integers");
  }
  return values;
}

std::vector<double> Hdf5File::Reals(const std::string& path, std::size_t max_size) const {
  const Hdf5Handle dataset = OpenDataset(path);
  Hdf5Handle type(H5Dget_type(dataset.get()), H5Tclose);
  const H5T_class_t kind = H5Tget_class(type.get());
  if (kind != H5T_FLOAT && kind != H5T_INTEGER) Fail(path, "must hold numbers");
  std::vector<double> values(Extent(dataset, path, max_size));
  if (!values.empty() &&
      H5Dread(dataset.get(), H5T_NATIVE_DOUBLE, H5S_ALL, H5S_ALL, H5P_DEFAULT, values.data()) < 0) {
    Fail(path, "HDF5 cannot read the numbers");
  }
  return values;
}

long long Hdf5File::Integer(const std::string& path) const {
  const std::vector<long long> values = Integers(path, 1);
  if (values.size() != 1) Fail(path, "must hold one integer, has none");
  return values[0];
}

std::string Hdf5File::OptionalString(const std::string& path) const {
  if (!Has(path)) return "";
  Hdf5Handle dataset(H5Dopen2(file_.get(), path.c_str(), H5P_DEFAULT), H5Dclose);
  if (!dataset.valid()) return "";
  Hdf5Handle type(H5Dget_type(dataset.get()), H5Tclose);
  if (H5Tget_class(type.get()) != H5T_STRING || H5Tis_variable_str(type.get()) > 0) return "";
  const std::size_t size = H5Tget_size(type.get());
  if (size == 0 || size > (1u << 16)) return "";
  std::string text(size, '\0');
  if (H5Dread(dataset.get(), type.get(), H5S_ALL, H5S_ALL, H5P_DEFAULT, text.data()) < 0) {
    return "";
  }
  text.resize(text.find('\0') == std::string::npos ? text.size() : text.find('\0'));
  return text;
}

void Hdf5File::MakeGroup(const std::string& path) const {
  Hdf5Handle group(H5Gcreate2(file_.get(), path.c_str(), H5P_DEFAULT, H5P_DEFAULT, H5P_DEFAULT),
                   H5Gclose);
  if (!group.valid()) Fail(path, "cannot create the group");
}

namespace {

void WriteDataset(hid_t file, const std::string& path, hid_t type, const void* data,
                  std::size_t size, const std::string& name) {
  const hsize_t dims = size;
  Hdf5Handle space(H5Screate_simple(1, &dims, nullptr), H5Sclose);
  Hdf5Handle dataset(
      H5Dcreate2(file, path.c_str(), type, space.get(), H5P_DEFAULT, H5P_DEFAULT, H5P_DEFAULT),
      H5Dclose);
  if (!space.valid() || !dataset.valid() ||
      (size > 0 && H5Dwrite(dataset.get(), type, H5S_ALL, H5S_ALL, H5P_DEFAULT, data) < 0)) {
    throw InputError(name, path, "cannot write the dataset");
  }
}

}  // namespace

void Hdf5File::WriteIntegers(const std::string& path, const std::vector<int>& values) const {
  WriteDataset(file_.get(), path, H5T_NATIVE_INT, values.data(), values.size(), name_);
}

void Hdf5File::WriteReals(const std::string& path, const double* values, std::size_t size) const {
  WriteDataset(file_.get(), path, H5T_NATIVE_DOUBLE, values, size, name_);
}

// As H5LTmake_dataset_string writes it (FCLIB's writer): a scalar fixed-length C string.
void Hdf5File::WriteString(const std::string& path, const std::string& text) const {
  Hdf5Handle type(H5Tcopy(H5T_C_S1), H5Tclose);
  H5Tset_size(type.get(), text.size() + 1);
  H5Tset_strpad(type.get(), H5T_STR_NULLTERM);
  Hdf5Handle space(H5Screate(H5S_SCALAR), H5Sclose);
  Hdf5Handle dataset(H5Dcreate2(file_.get(), path.c_str(), type.get(), space.get(), H5P_DEFAULT,
                                H5P_DEFAULT, H5P_DEFAULT),
                     H5Dclose);
  if (!dataset.valid() ||
      H5Dwrite(dataset.get(), type.get(), H5S_ALL, H5S_ALL, H5P_DEFAULT, text.c_str()) < 0) {
    Fail(path, "cannot write the string");
  }
}

void Hdf5File::Close() {
  if (!file_.valid()) return;
  const herr_t flushed = H5Fflush(file_.get(), H5F_SCOPE_LOCAL);
  const herr_t closed = H5Fclose(file_.release());
  if (flushed < 0 || closed < 0) Fail("", "HDF5 could not finish writing the file");
}

}  // namespace cb::io
