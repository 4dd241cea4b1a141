// SPDX-License-Identifier: MIT
// OFF reader: header, counts, vertices, then faces as "n i0 i1 ... i(n-1)".
#include "off_mesh.h"

#include <cstdio>
#include <fstream>
#include <sstream>

namespace sc::demo {

namespace {

/// Next line that is neither empty nor a comment.
bool nextLine(std::istream& in, std::string& line) {
  while (std::getline(in, line)) {
    const std::size_t p = line.find_first_not_of(" \t\r");
    if (p != std::string::npos && line[p] != '#') return true;
  }
  return false;
}

}  // namespace

MeshData readOff(const std::string& path) {
  MeshData mesh;
  std::ifstream in(path);
  std::string line;
  if (!in || !nextLine(in, line) || line.rfind("OFF", 0) != 0) {
    std::fprintf(stderr, "%s: not an OFF file\n", path.c_str());
    return mesh;
  }
  std::istringstream header(line.substr(3));
  int nv = 0, nf = 0;
  if (!(header >> nv >> nf)) {
    if (!nextLine(in, line)) return mesh;
    std::istringstream counts(line);
    counts >> nv >> nf;
  }
  for (int i = 0; i < nv && nextLine(in, line); ++i) {
    std::istringstream s(line);
    Vec3 v;
    s >> v.x() >> v.y() >> v.z();
    mesh.vertices.push_back(v);
  }
  for (int i = 0; i < nf && nextLine(in, line); ++i) {
    std::istringstream s(line);
    int n = 0;
    s >> n;
    std::vector<int> idx(static_cast<std::size_t>(n > 0 ? n : 0));
    for (int& k : idx) s >> k;
    for (std::size_t k = 1; k + 1 < idx.size(); ++k) mesh.triangles.emplace_back(idx[0], idx[k], idx[k + 1]);
  }
  if (static_cast<int>(mesh.vertices.size()) != nv) {
    std::fprintf(stderr, "%s: truncated\n", path.c_str());
    return MeshData();
  }
  return mesh;
}

}  // namespace sc::demo
