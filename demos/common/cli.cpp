// SPDX-License-Identifier: MIT
#include "cli.h"

#include <cstdio>
#include <cstdlib>

namespace sc::demo {

bool nextValue(int argc, char** argv, int& i, std::string& out) {
  if (i + 1 >= argc) return false;
  out = argv[++i];
  return true;
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

}  // namespace sc::demo
