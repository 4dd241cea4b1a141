// SPDX-License-Identifier: MIT
#include "options.h"

#include <cmath>
#include <cstdio>
#include <cstdlib>

#include "smartcollision/bullet/bullet.h"
#include "smartcollision/haptics/virtual_coupling.h"

namespace sc::demo::haptic {
namespace {

const std::string kScriptPrefix = "script:";

void usage(const char* program) {
  std::fprintf(stderr,
               "usage: %s [--scene peg|cavity] [--device mouse|spacemouse|script:FILE]\n"
               "          [--physics-hz HZ] [--loop] [--headless [--lockstep] [--seconds S] "
               "[--png F] [--json F] [--wrench-log F]]\n"
               "  --loop      play the script back and forth until --seconds (a soak)\n"
               "  --lockstep  haptic samples and physics steps in turn on simulated time,\n"
               "              one thread: the same outcome on any machine load\n",
               program);
}

}  // namespace

bool parse(int argc, char** argv, Options& o) {
  for (int i = 1; i < argc; ++i) {
    if (readHeadlessOption(argc, argv, i, o)) continue;
    const std::string a = argv[i];
    std::string v;
    auto value = [&](std::string& out) { return nextValue(argc, argv, i, out); };
    if (a == "--scene" && value(v) && (v == "peg" || v == "cavity")) {
      o.scene = v;
    } else if (a == "--device" && value(v)) {
      // An installed script is found by its name.
      o.device = v.rfind(kScriptPrefix, 0) == 0
                     ? kScriptPrefix + demoScript(v.substr(kScriptPrefix.size()))
                     : v;
    } else if (a == "--physics-hz" && value(v)) {
      o.physics_hz = std::atof(v.c_str());
    } else if (a == "--wrench-log" && value(v)) {
      o.wrench_log = v;
    } else if (a == "--loop") {
      o.loop = true;
    } else if (a == "--lockstep") {
      o.lockstep = true;
    } else {
      usage(argv[0]);
      return false;
    }
  }
  if (o.physics_hz == 0.0) o.physics_hz = o.scene == "cavity" ? 500.0 : 1000.0;
  return o.seconds >= 0.0 && std::isfinite(o.seconds) && o.physics_hz >= 100.0 &&
         o.physics_hz <= 10000.0;
}

std::string scriptFile(const Options& o) {
  return o.device.rfind(kScriptPrefix, 0) == 0 ? o.device.substr(kScriptPrefix.size()) : "";
}

double defaultSeconds(const Options& o) {
  const std::string file = scriptFile(o);
  double length = 0.0;
  if (!file.empty()) {
    auto s = sc::haptics::PoseScript::load(file);
    if (s.ok()) length = s.value().duration();
  }
  return length > 0 ? length + 1.0 : 10.0;
}

}  // namespace sc::demo::haptic
