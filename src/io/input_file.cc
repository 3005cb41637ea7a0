#include "io/input_file.h"

#include <filesystem>
#include <fstream>
#include <sstream>

#include "io/input_error.h"

namespace cb::io {

namespace {

// "a directory", "a FIFO", ... for the message of a refused file.
std::string KindOf(std::filesystem::file_type type) {
  switch (type) {
    case std::filesystem::file_type::directory:
      return "a directory";
    case std::filesystem::file_type::fifo:
      return "a FIFO";
    case std::filesystem::file_type::character:
    case std::filesystem::file_type::block:
      return "a device";
    case std::filesystem::file_type::socket:
      return "a socket";
    default:
      return "not a regular file";
  }
}

}  // namespace

std::string ReadInputFile(const std::string& path, const std::string& what,
                          std::uintmax_t max_bytes, const std::string& lifted_by) {
  std::error_code ec;
  const std::filesystem::file_type type = std::filesystem::status(path, ec).type();
  if (type == std::filesystem::file_type::not_found) {
    throw InputError(path, "", "cannot open the " + what + ": no such file");
  }
  if (!ec && type != std::filesystem::file_type::regular) {
    throw InputError(path, "", "is " + KindOf(type) + ", not a " + what);
  }
  const std::uintmax_t size = std::filesystem::file_size(path, ec);
  if (max_bytes > 0 && !ec && size > max_bytes) {
    throw InputError(path, "",
                     "the " + what + " is " + std::to_string(size) + " bytes, more than the " +
                         std::to_string(max_bytes) + " bytes a " + what + " may have" +
                         (lifted_by.empty() ? "" : " without " + lifted_by));
  }
  std::ifstream in(path, std::ios::binary);
  if (!in) throw InputError(path, "", "cannot open the " + what);
  std::ostringstream text;
  text << in.rdbuf();
  if (in.bad()) throw InputError(path, "", "cannot read the " + what);
  return text.str();
}

}  // namespace cb::io
