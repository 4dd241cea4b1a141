// SPDX-License-Identifier: MIT
// Files of the cache tests: unique paths under $TMPDIR (or /tmp), whole-file reads
// and writes, and a file removed before and after a test.
#pragma once

#include <unistd.h>

#include <cstdint>
#include <cstdio>
#include <cstdlib>
#include <fstream>
#include <iterator>
#include <string>
#include <vector>

namespace sc::test {

/// $TMPDIR/<prefix>_<pid>_<name>: distinct per suite and per process.
inline std::string tempPath(const std::string& prefix, const std::string& name) {
  const char* dir = std::getenv("TMPDIR");
  return std::string(dir != nullptr ? dir : "/tmp") + "/" + prefix + "_" +
         std::to_string(::getpid()) + "_" + name;
}

/// The whole file (empty when it cannot be read), as bytes or as a string.
template <class Bytes = std::vector<std::uint8_t>>
Bytes readBytes(const std::string& path) {
  std::ifstream in(path, std::ios::binary);
  return {std::istreambuf_iterator<char>(in), std::istreambuf_iterator<char>()};
}

inline void writeBytes(const std::string& path, const std::vector<std::uint8_t>& bytes) {
  std::ofstream out(path, std::ios::binary | std::ios::trunc);
  out.write(reinterpret_cast<const char*>(bytes.data()),
            static_cast<std::streamsize>(bytes.size()));
}

/// Removes the file when the test starts and when it ends.
struct TempFile {
  TempFile(const std::string& prefix, const std::string& name) : path(tempPath(prefix, name)) {
    std::remove(path.c_str());
  }
  ~TempFile() { std::remove(path.c_str()); }
  TempFile(const TempFile&) = delete;
  TempFile& operator=(const TempFile&) = delete;
  std::string path;
};

}  // namespace sc::test
