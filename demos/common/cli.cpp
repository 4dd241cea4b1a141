// SPDX-License-Identifier: MIT
#include "cli.h"

#include <sys/resource.h>
#include <sys/stat.h>
#include <unistd.h>

#include <cstdio>
#include <cstdlib>

namespace sc::demo {

bool nextValue(int argc, char** argv, int& i, std::string& out) {
  if (i + 1 >= argc) return false;
  out = argv[++i];
  return true;
}

long residentKb() {
  long pages = 0, resident = 0;
  FILE* f = std::fopen("/proc/self/statm", "r");
  if (f == nullptr) return 0;
  if (std::fscanf(f, "%ld %ld", &pages, &resident) != 2) resident = 0;
  std::fclose(f);
  return resident * (sysconf(_SC_PAGESIZE) / 1024);
}

long peakResidentKb() {
  rusage u{};
  getrusage(RUSAGE_SELF, &u);
  return u.ru_maxrss;
}

bool readHeadlessOption(int argc, char** argv, int& i, HeadlessOptions& o) {
  const std::string a = argv[i];
  std::string v;
  if (a == "--headless") {
    o.headless = true;
  } else if (a == "--seconds" && nextValue(argc, argv, i, v)) {
    o.seconds = std::atof(v.c_str());
  } else if (a == "--png" && nextValue(argc, argv, i, v)) {
    o.png = v;
  } else if (a == "--json" && nextValue(argc, argv, i, v)) {
    o.json = v;
  } else {
    return false;
  }
  return true;
}

bool emitMetrics(const std::string& metrics, const std::string& path) {
  std::fputs(metrics.c_str(), stdout);
  if (path.empty()) return true;
  FILE* f = std::fopen(path.c_str(), "w");
  if (f == nullptr) return false;
  std::fputs(metrics.c_str(), f);
  return std::fclose(f) == 0;
}

namespace {

bool isFile(const std::string& path) {
  struct stat st {};
  return ::stat(path.c_str(), &st) == 0 && S_ISREG(st.st_mode);
}

/// <folder of the running executable>/<SC_DEMO_DATA_FROM_BIN>/<kind>/<file>, or ""
/// when /proc/self/exe cannot be read.
std::string installedData(const std::string& kind, const std::string& file) {
  char exe[4096];
  const ssize_t n = ::readlink("/proc/self/exe", exe, sizeof exe - 1);
  if (n <= 0) return "";
  const std::string path(exe, static_cast<std::size_t>(n));
  const std::string base = file.substr(file.find_last_of('/') + 1);
  return path.substr(0, path.find_last_of('/') + 1) + SC_DEMO_DATA_FROM_BIN "/" + kind + "/" + base;
}

}  // namespace

std::string demoMesh(const std::string& file) {
  const std::string installed = installedData("meshes", file);
  return isFile(installed) ? installed : std::string(SC_DEMO_MESH_DIR "/") + file;
}

std::string demoScript(const std::string& path) {
  if (isFile(path)) return path;
  const std::string installed = installedData("scripts", path);
  return isFile(installed) ? installed : path;
}

}  // namespace sc::demo
