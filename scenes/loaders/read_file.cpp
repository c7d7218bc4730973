// readInputFile.
#include "scenes/loaders/read_file.h"

#include <cerrno>
#include <cstring>
#include <filesystem>
#include <fstream>

#include "core/error.h"

namespace rc {

namespace {

// Checks the file, then reads it into a container of its size made by `make`.
template <typename Container, typename Make>
Container readChecked(const std::string& path, Make make) {
  namespace fs = std::filesystem;
  std::error_code ec;
  const fs::file_status status = fs::status(path, ec);
  // A missing file, or one in a missing folder, is "no such file"; anything else that stops
  // the look-up (a symbolic link loop, a folder without search permission) says what it is.
  if (ec && ec != std::errc::no_such_file_or_directory && ec != std::errc::not_a_directory) {
    throw ioError(path, "cannot read: " + ec.message());
  }
  if (ec || !fs::exists(status)) throw ioError(path, "cannot read: no such file");
  if (!fs::is_regular_file(status)) throw ioError(path, "cannot read: not a regular file");
  const std::uintmax_t size = fs::file_size(path, ec);
  if (ec) throw ioError(path, "cannot read: " + ec.message());
  if (size > kMaxInputFileBytes) {
    throw badInput(path, "file of " + std::to_string(size) + " bytes exceeds the 1 GiB limit");
  }
  std::ifstream in(path, std::ios::binary);
  if (!in) throw ioError(path, std::string("cannot read: ") + std::strerror(errno));
  Container bytes = make(std::size_t(size));
  in.read(bytes.data(), std::streamsize(size));
  if (in.gcount() != std::streamsize(size)) throw ioError(path, "cannot read: short read");
  return bytes;
}

}  // namespace

std::string readInputFile(const std::string& path) {
  return readChecked<std::string>(path, [](std::size_t size) { return std::string(size, '\0'); });
}

PlaneVector<char> readLargeInputFile(const std::string& path) {
  return readChecked<PlaneVector<char>>(path, [](std::size_t size) {
    PlaneVector<char> bytes;
    bytes.resize(size);  // default-initialised: not written before the read
    return bytes;
  });
}

}  // namespace rc
