// SPDX-License-Identifier: MIT
// Command-line pieces every demo shares: the headless options and the metrics output.
#pragma once

#include <string>

namespace sc::demo {

/// --headless [--seconds S] [--png F] [--json F]; a demo's options derive from it and
/// set their own default duration.
struct HeadlessOptions {
  bool headless = false;
  double seconds = 0.0;
  std::string png, json;
};

/// The argument after argv[i] (i moves to it); false when there is none.
bool nextValue(int argc, char** argv, int& i, std::string& out);

/// Reads argv[i] when it is one of HeadlessOptions' flags (with its value); false for
/// any other argument or a missing value.
bool readHeadlessOption(int argc, char** argv, int& i, HeadlessOptions& o);

/// Prints `metrics` and writes them to `path` unless it is empty; false when the file
/// cannot be written.
bool emitMetrics(const std::string& metrics, const std::string& path);

}  // namespace sc::demo
