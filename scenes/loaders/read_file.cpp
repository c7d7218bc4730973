// readInputFile.
#include "scenes/loaders/read_file.h"

#include <cerrno>
#include <cstring>
#include <filesystem>
#include <fstream>

#include "core/error.h"

namespace rc {

std::string readInputFile(const std::string& path) {
  namespace fs = std::filesystem;
  std::error_code ec;
  const fs::file_status status = fs::status(path, ec);
  if (ec || !fs::exists(status)) throw ioError(path, "cannot read: no such file");
  if (!fs::is_regular_file(status)) throw ioError(path, "cannot read: not a regular file");
  const std::uintmax_t size = fs::file_size(path, ec);
  if (ec) throw ioError(path, "cannot read: " + ec.message());
  if (size > kMaxInputFileBytes) {
    throw badInput(path, "file of " + std::to_string(size) + " bytes exceeds the 1 GiB limit");
  }
  std::ifstream in(path, std::ios::binary);
  if (!in) throw ioError(path, std::string("cannot read: ") + std::strerror(errno));
  std::string text(size, '\0');
  in.read(text.data(), std::streamsize(size));
  if (in.gcount() != std::streamsize(size)) throw ioError(path, "cannot read: short read");
  return text;
}

}  // namespace rc
