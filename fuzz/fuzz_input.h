// Shared by the fuzz targets: the loaders read files, so each input is written to a file in a
// per-process temporary folder first. A rejection (rc::Error) is the expected outcome for
// most inputs; anything else escaping, a crash or a sanitizer report is a finding.
#pragma once

#include <unistd.h>

#include <cstdint>
#include <filesystem>
#include <fstream>
#include <string>

namespace rc::fuzz {

inline std::string writeInput(const std::string& name, const std::uint8_t* data, std::size_t size) {
  static const std::filesystem::path dir = [] {
    const auto path = std::filesystem::temp_directory_path() / ("rc_fuzz_" + std::to_string(getpid()));
    std::filesystem::create_directories(path);
    return path;
  }();
  const std::filesystem::path path = dir / name;
  std::ofstream(path, std::ios::binary | std::ios::trunc).write(reinterpret_cast<const char*>(data), std::streamsize(size));
  return path.string();
}

}  // namespace rc::fuzz
