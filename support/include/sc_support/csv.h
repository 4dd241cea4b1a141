// SPDX-License-Identifier: MIT
// CSV files of measured rows (the benches' figures under docs/benchmarks/): a header,
// then one printf-formatted row per call.
#pragma once

#include <cstdio>
#include <string>

namespace sc::support {

class CsvFile {
 public:
  /// Creates `path` and writes `header` (column names, comma separated) as its first
  /// line. When the file cannot be created, says so on stderr and ok() is false; rows
  /// are then dropped.
  CsvFile(const std::string& path, const char* header);
  ~CsvFile();
  CsvFile(const CsvFile&) = delete;
  CsvFile& operator=(const CsvFile&) = delete;

  bool ok() const { return file_ != nullptr; }
  /// One line: `format` and its arguments as printf writes them, then a newline.
  void row(const char* format, ...) __attribute__((format(printf, 2, 3)));

 private:
  std::FILE* file_;
};

/// A text field as CSV needs it: quoted (with inner quotes doubled) when it holds a
/// comma, a quote or a newline, as it is otherwise.
std::string csvField(const std::string& text);

}  // namespace sc::support
