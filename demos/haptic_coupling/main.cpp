// SPDX-License-Identifier: MIT
// Haptic coupling demo (manual 9-10.3 on Bullet): a 6-DOF device drives one rigid
// body through a virtual spring-damper. Three loops:
//   haptic thread   1 kHz: poll the device, compute the coupling reaction from the
//                   latest body state, hand it to the device;
//   physics thread  1 kHz, 500 Hz for the cavity (--physics-hz): apply the coupling
//                   to the body with the latest device pose, step Bullet + SmartCollision;
//   graphics        the GLUT loop in the main thread (not run with --headless).
// Files by concern: options (command line), scenes (the world and its bodies),
// handoff (the seqlocks between the loops), coupling (the haptic and physics loops),
// metrics (what they measure, the JSON), render (the viewer's items and overlay).
// Scenes: `peg` (square peg into a block with a square through-hole, 2 mm clearance
// per side) and `cavity` (the bunny, 75k triangles, into a cup).
// With --loop a recorded script plays back and forth until --seconds: the soak of
// bench/soak_haptic.sh, whose NaN, energy and memory figures the JSON reports.
#include <atomic>
#include <chrono>
#include <cstdio>
#include <memory>
#include <string>
#include <thread>

#include "../common/device.h"
#include "../common/viewer.h"
#include "coupling.h"
#include "options.h"
#include "render.h"
#include "scenes.h"

namespace sc::demo::haptic {
namespace {

/// The device named by the options; a script plays on `sim_clock` with --lockstep.
std::unique_ptr<Device> openDevice(const Options& options, std::atomic<double>& sim_clock) {
  std::string error;
  std::unique_ptr<Device> device;
  const std::string script = scriptFile(options);
  if (!script.empty()) {
    ScriptPlayback playback;
    playback.ping_pong = options.loop;
    playback.log_wrenches = !options.wrench_log.empty();  // else memory would grow with time
    if (options.lockstep) playback.clock = [&sim_clock] { return sim_clock.load(); };
    device = makeScriptDevice(script, error, playback);
  } else {
    device = makeDevice(options.device, error);
  }
  if (!device) std::fprintf(stderr, "device: %s\n", error.c_str());
  return device;
}

bool writeWrenchLog(const WrenchLog& log, const std::string& path) {
  FILE* f = std::fopen(path.c_str(), "w");
  if (f == nullptr) return false;
  std::fprintf(f, "# t fx fy fz tx ty tz (reaction rendered to the device)\n");
  for (std::size_t i = 0; i < log.t.size(); ++i) {
    const Wrench& w = log.wrench[i];
    std::fprintf(f, "%.6f %.6g %.6g %.6g %.6g %.6g %.6g\n", log.t[i], w.force[0], w.force[1],
                 w.force[2], w.torque[0], w.torque[1], w.torque[2]);
  }
  std::fclose(f);
  return true;
}

/// --headless: the run, its metrics, the wrench log and the PNG.
int runHeadless(int argc, char** argv, const Options& options, CouplingLoops& loops,
                Renderer& renderer, const ViewerCallbacks& cb, std::atomic<double>& sim_clock) {
  const double seconds = options.seconds > 0 ? options.seconds : defaultSeconds(options);
  if (options.lockstep) {
    loops.runLockstep(seconds, sim_clock);
  } else {
    loops.start();
    std::this_thread::sleep_for(std::chrono::duration<double>(seconds));
    loops.stop();
  }
  if (!emitMetrics(loops.json(options.scene), options.json)) return 1;
  const WrenchLog* log = wrenchLogOf(loops.device());
  if (!options.wrench_log.empty() && log != nullptr && !writeWrenchLog(*log, options.wrench_log))
    return 1;
  if (!options.png.empty() &&
      !renderToPng(argc, argv, cb, renderer.targetY(), renderer.distance(), options.png))
    return 1;
  return 0;
}

/// The demo: 0 on success, 1 when an output cannot be written, 2 on bad arguments.
int run(int argc, char** argv) {
  Options options;
  if (!parse(argc, argv, options)) return 2;
  const bool script = !scriptFile(options).empty();
  if ((options.headless || options.loop) && !script) {
    std::fprintf(stderr, "--headless and --loop need --device script:FILE\n");
    return 2;
  }
  if (options.lockstep && !options.headless) {
    std::fprintf(stderr, "--lockstep needs --headless\n");
    return 2;
  }
  std::atomic<double> sim_clock{0.0};  // --lockstep: the script's clock
  std::unique_ptr<Device> device = openDevice(options, sim_clock);
  if (!device) return 2;
  HapticScene scene(options.scene, 1.0 / options.physics_hz);
  CouplingLoops loops(scene, std::move(device), options.physics_hz);
  Renderer renderer(options.scene, scene, loops);
  ViewerCallbacks cb;
  cb.collect = [&](std::vector<DrawItem>& items) { renderer.collect(items); };
  cb.overlay = [&] { return renderer.overlay(); };
  if (options.headless) return runHeadless(argc, argv, options, loops, renderer, cb, sim_clock);
  bool attached = false;
  cb.step = [&] {
    if (!attached) {  // the window exists now: window-fed devices take their events
      loops.device().attachWindow();
      attached = true;
    }
    std::this_thread::sleep_for(std::chrono::milliseconds(10));  // about 60-100 frames per second
  };
  cb.key = [&](unsigned char k) { loops.device().key(k); };
  loops.start();
  runViewer(argc, argv, "SmartCollision haptic coupling", cb, renderer.targetY(),
            renderer.distance());
  return 0;
}

}  // namespace
}  // namespace sc::demo::haptic

int main(int argc, char** argv) { return sc::demo::haptic::run(argc, argv); }
