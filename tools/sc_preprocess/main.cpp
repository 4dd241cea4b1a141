// SPDX-License-Identifier: MIT
// sc-preprocess: preprocesses a mesh file (OFF, OBJ, STL and PLY through strict readers,
// other formats through assimp) into a SmartCollision cache file and prints the
// decomposition's statistics.
//
//   sc-preprocess MESH [-o CACHE] [--soup] [--threads N]
//
// All meshes of the file are merged into one piece (node transforms applied,
// coincident positions welded). Exit codes: 0 ok, 1 bad input or geometry (or the
// cache could not be written), 2 usage, 130 interrupted (Ctrl-C cancels the build and
// writes no cache). Progress goes to stderr: a bar with the time left on a terminal,
// plain lines otherwise. A malformed file is one line on stderr naming
// the file and the problem. Uses the public API only.
#include <sys/stat.h>
#include <unistd.h>

#include <cerrno>
#include <chrono>
#include <cmath>
#include <csignal>
#include <cstdio>
#include <cstdlib>
#include <string>
#include <utility>

#include "mesh_import.h"
#include "smartcollision/model.h"

namespace {

constexpr int kExitOk = 0;
constexpr int kExitBadInput = 1;
constexpr int kExitUsage = 2;
constexpr int kExitInterrupted = 130;  // the shell's code for SIGINT

struct Options {
  std::string mesh;
  std::string cache;
  bool soup = false;
  int threads = 0;  ///< BuildOptions::threads: 0 = one per hardware thread
};

void printUsage(std::FILE* out) {
  std::fprintf(out,
               "usage: sc-preprocess MESH [-o CACHE] [--soup] [--threads N]\n"
               "  MESH         OFF, OBJ, STL or PLY file; all its meshes make one piece\n"
               "  -o CACHE     write (or reuse) the preprocessing cache file\n"
               "  --soup       treat the mesh as a triangle soup (default: closed polyhedron)\n"
               "  --threads N  build on N threads, 0 (default) = one per hardware thread;\n"
               "               the cache file is the same for every N\n");
}

/// A whole number in [0, sc::kMaxBuildThreads], or -1.
int parseThreads(const char* text) {
  char* end = nullptr;
  errno = 0;
  const long n = std::strtol(text, &end, 10);
  const bool whole = end != text && *end == '\0' && errno == 0;
  return whole && n >= 0 && n <= sc::kMaxBuildThreads ? static_cast<int>(n) : -1;
}

/// False on a usage error (message printed).
bool parseArguments(int argc, char** argv, Options& options) {
  for (int i = 1; i < argc; ++i) {
    const std::string arg = argv[i];
    if (arg == "-h" || arg == "--help") {
      printUsage(stdout);
      std::exit(kExitOk);
    } else if (arg == "-o") {
      if (i + 1 >= argc || !options.cache.empty()) {
        std::fprintf(stderr, "sc-preprocess: -o needs one file name\n");
        return false;
      }
      options.cache = argv[++i];
    } else if (arg == "--soup") {
      options.soup = true;
    } else if (arg == "--threads") {
      options.threads = i + 1 < argc ? parseThreads(argv[++i]) : -1;
      if (options.threads < 0) {
        std::fprintf(stderr, "sc-preprocess: --threads needs a whole number from 0 to %d\n",
                     sc::kMaxBuildThreads);
        return false;
      }
    } else if (!arg.empty() && arg[0] == '-') {
      std::fprintf(stderr, "sc-preprocess: unknown option '%s'\n", arg.c_str());
      return false;
    } else if (options.mesh.empty()) {
      options.mesh = arg;
    } else {
      std::fprintf(stderr, "sc-preprocess: more than one mesh given\n");
      return false;
    }
  }
  if (options.mesh.empty()) {
    std::fprintf(stderr, "sc-preprocess: no mesh given\n");
    return false;
  }
  return true;
}

using Clock = std::chrono::steady_clock;

/// Set by SIGINT: the build is cancelled between patches, so no cache is half-written.
volatile std::sig_atomic_t interrupted = 0;

void onInterrupt(int) { interrupted = 1; }

/// "about 12 s left" from the rate so far; empty while too early to tell.
std::string timeLeft(double fraction, double elapsed) {
  if (fraction < 0.02 || fraction >= 1.0 || elapsed < 0.5) return "";
  const double left = elapsed * (1.0 - fraction) / fraction;
  char text[48];
  if (left < 90.0) {
    std::snprintf(text, sizeof text, "about %.0f s left", std::ceil(left));
  } else {
    std::snprintf(text, sizeof text, "about %.0f min left", std::ceil(left / 60.0));
  }
  return text;
}

/// Progress on stderr, so stdout keeps only the statistics. On a terminal: a bar
/// with the time left, redrawn at most every whole percent. Otherwise (a log): one
/// plain line per stage and per tenth.
class ProgressDisplay {
 public:
  explicit ProgressDisplay(bool terminal) : terminal_(terminal), start_(Clock::now()) {}

  void operator()(double fraction, const char* stage) {
    const int percent = static_cast<int>(100.0 * fraction);
    const bool new_stage = stage_ != stage;
    const int step = terminal_ ? 1 : 10;
    if (!new_stage && percent / step == shown_ / step) return;
    shown_ = percent;
    stage_ = stage;
    const double elapsed = std::chrono::duration<double>(Clock::now() - start_).count();
    const std::string left = timeLeft(fraction, elapsed);
    if (terminal_) {
      constexpr int kWidth = 40;
      const int filled = percent * kWidth / 100;
      std::fprintf(stderr, "\r[%s%s] %3d%% %-18s %-20s", std::string(filled, '#').c_str(),
                   std::string(kWidth - filled, ' ').c_str(), percent, stage, left.c_str());
    } else {
      std::fprintf(stderr, "sc-preprocess: %3d%% %s, %.1f s%s%s\n", percent, stage, elapsed,
                   left.empty() ? "" : ", ", left.c_str());
    }
    std::fflush(stderr);
  }
  void finish() {
    if (terminal_ && shown_ >= 0) std::fprintf(stderr, "\n");
  }

 private:
  bool terminal_;
  Clock::time_point start_;
  int shown_ = -1;
  std::string stage_;
};

}  // namespace

int main(int argc, char** argv) {
  Options options;
  if (!parseArguments(argc, argv, options)) {
    printUsage(stderr);
    return kExitUsage;
  }
  // Refused before the work: the library would not replace it either.
  struct stat cache {};
  if (!options.cache.empty() && ::stat(options.cache.c_str(), &cache) == 0 &&
      !S_ISREG(cache.st_mode)) {
    std::fprintf(stderr, "sc-preprocess: the cache file '%s' is not a regular file\n",
                 options.cache.c_str());
    return kExitBadInput;
  }
  const auto start = std::chrono::steady_clock::now();
  sc::Result<sc::tools::ImportedMesh> imported = sc::tools::importMeshFile(options.mesh);
  if (!imported.ok()) {
    std::fprintf(stderr, "sc-preprocess: %s\n", imported.status().message().c_str());
    return kExitBadInput;
  }
  const int skipped = imported.value().skipped;
  const double read_seconds =
      std::chrono::duration<double>(std::chrono::steady_clock::now() - start).count();

  ProgressDisplay bar(::isatty(STDERR_FILENO) == 1);
  sc::BuildOptions build;
  build.cache_file = options.cache;
  build.threads = options.threads;
  build.progress = [&bar](double fraction, const char* stage) { bar(fraction, stage); };
  build.cancel = [] { return interrupted != 0; };
  std::signal(SIGINT, onInterrupt);
  const sc::ModelKind kind =
      options.soup ? sc::ModelKind::TriangleSoup : sc::ModelKind::ClosedPolyhedron;
  const sc::Result<sc::PiecePtr> piece =
      sc::buildPiece(kind, std::move(imported.value().mesh), build);
  bar.finish();
  std::signal(SIGINT, SIG_DFL);
  if (!piece.hasValue() && interrupted != 0) {
    std::fprintf(stderr, "sc-preprocess: interrupted, no cache written\n");
    return kExitInterrupted;
  }
  if (!piece.hasValue()) {
    std::fprintf(stderr, "sc-preprocess: '%s': %s: %s\n", options.mesh.c_str(),
                 sc::describe(piece.status().code()), piece.status().message().c_str());
    return kExitBadInput;
  }
  const sc::PieceStats& s = piece.value()->stats();
  std::printf("mesh            %s (%s)\n", options.mesh.c_str(),
              options.soup ? "triangle soup" : "closed polyhedron");
  std::printf("input           %d vertices, %d triangles", s.vertices, s.triangles);
  if (skipped > 0) std::printf(" (%d points or lines skipped)", skipped);
  std::printf("%s\n", s.flipped ? ", given inside out (flipped)" : "");
  std::printf("pieces          1\n");
  std::printf("patches         %d%s\n", s.patches,
              options.soup ? " (triangle leaves)"
              : s.convex   ? " (convex)"
                           : "");
  std::printf("virtual faces   %d\n", s.virtual_faces);
  std::printf("hull vertices   %d\n", s.hull_vertices);
  std::printf("tree depth      %d\n", s.tree_depth);
  std::printf("time            %.3f s preprocessing%s, %.3f s reading\n", s.seconds,
              s.from_cache ? " (from cache)" : "", read_seconds);
  if (!options.cache.empty()) {
    if (!piece.ok()) {
      std::fprintf(stderr, "sc-preprocess: %s\n", piece.status().message().c_str());
      return kExitBadInput;
    }
    std::printf("cache           %s %s\n", options.cache.c_str(),
                s.from_cache ? "(valid, reused)" : "(written)");
  }
  return kExitOk;
}
