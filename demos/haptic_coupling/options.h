// SPDX-License-Identifier: MIT
// The demo's command line.
#pragma once

#include <string>

#include "../common/cli.h"

namespace sc::demo::haptic {

/// seconds 0: the script's length + 1 s (headless), unlimited otherwise.
struct Options : HeadlessOptions {
  std::string scene = "peg";
  std::string device = "mouse";
  double physics_hz = 0.0;  ///< 0: 1000 Hz for peg, 500 Hz for cavity (75k triangles)
  std::string wrench_log;   ///< script device: the rendered wrenches, one line per sample
  bool loop = false;        ///< script device: play back and forth (a soak with --seconds)
  bool lockstep = false;    ///< headless: haptic and physics in turn on simulated time
};

/// Reads the arguments; false (with the usage on stderr) on an unknown or bad one.
bool parse(int argc, char** argv, Options& o);

/// The --device argument's script file, or "" for a live device.
std::string scriptFile(const Options& o);

/// Seconds of a headless run without --seconds: the script's length + 1 s (10 s
/// when it cannot be read).
double defaultSeconds(const Options& o);

}  // namespace sc::demo::haptic
