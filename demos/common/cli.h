// SPDX-License-Identifier: MIT
// Command-line pieces every demo shares: the headless options, the metrics output and
// where the demos' data files are.
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

/// Resident set size now [kB] (/proc/self/statm), 0 when unavailable.
long residentKb();
/// The largest resident set size so far [kB].
long peakResidentKb();

/// Prints `metrics` and writes them to `path` unless it is empty; false when the file
/// cannot be written.
bool emitMetrics(const std::string& metrics, const std::string& path);

/// A mesh the demos ship (`file`, e.g. "bunny00.off"): the installed copy
/// (<executable>/../share/smartcollision/meshes/, found from /proc/self/exe) when there
/// is one, else the copy in the source tree the demo was built from (.meshes/,
/// extracted by scripts/setup.sh).
std::string demoMesh(const std::string& file);

/// A script named on the command line: `path` when it exists, else the installed copy
/// of its file name (<executable>/../share/smartcollision/scripts/), else `path`.
std::string demoScript(const std::string& path);

}  // namespace sc::demo
