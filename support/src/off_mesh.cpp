// SPDX-License-Identifier: MIT
#include "sc_support/off_mesh.h"

#include <cmath>
#include <cstdio>
#include <fstream>
#include <sstream>
#include <utility>
#include <vector>

namespace sc::support {
namespace {

Status bad(const std::string& what) { return {ErrorCode::InvalidArgument, "OFF: " + what}; }

/// The lines of `text` with comments removed and blank lines dropped; each line is
/// kept whole because a face's extra numbers must not spill into the next face.
std::vector<std::string> dataLines(const std::string& text) {
  std::vector<std::string> lines;
  std::istringstream in(text);
  std::string line;
  while (std::getline(in, line)) {
    const std::size_t hash = line.find('#');
    if (hash != std::string::npos) line.erase(hash);
    if (line.find_first_not_of(" \t\r") != std::string::npos) lines.push_back(line);
  }
  return lines;
}

}  // namespace

Result<MeshData> parseOff(const std::string& text) {
  const std::vector<std::string> lines = dataLines(text);
  std::size_t next = 0;
  if (lines.empty()) return bad("empty file");
  std::istringstream header(lines[next++]);
  std::string magic;
  header >> magic;
  if (magic != "OFF") return bad("missing OFF header (found '" + magic + "')");
  long long nv = -1, nf = -1, ne = -1;
  if (!(header >> nv)) {
    if (next >= lines.size()) return bad("missing counts");
    std::istringstream counts(lines[next++]);
    if (!(counts >> nv >> nf)) return bad("unreadable counts");
    counts >> ne;
  } else if (!(header >> nf)) {
    return bad("unreadable counts");
  }
  if (nv < 0 || nf < 0 || nv > (1LL << 30) || nf > (1LL << 30)) return bad("bad counts");
  if (lines.size() - next < static_cast<std::size_t>(nv + nf)) return bad("file ends early");

  MeshData mesh;
  mesh.vertices.reserve(static_cast<std::size_t>(nv));
  for (long long i = 0; i < nv; ++i) {
    std::istringstream in(lines[next++]);
    double x, y, z;
    if (!(in >> x >> y >> z)) return bad("unreadable vertex " + std::to_string(i));
    if (!std::isfinite(x) || !std::isfinite(y) || !std::isfinite(z)) {
      return bad("non-finite vertex " + std::to_string(i));
    }
    mesh.vertices.emplace_back(x, y, z);
  }
  mesh.triangles.reserve(static_cast<std::size_t>(nf));
  for (long long i = 0; i < nf; ++i) {
    std::istringstream in(lines[next++]);
    long long corners = 0;
    if (!(in >> corners) || corners < 3)
      return bad("face " + std::to_string(i) + " has < 3 corners");
    std::vector<int> ids;
    for (long long k = 0; k < corners; ++k) {
      long long id = -1;
      if (!(in >> id)) return bad("face " + std::to_string(i) + " is missing indices");
      if (id < 0 || id >= nv) return bad("face " + std::to_string(i) + " has index out of range");
      ids.push_back(static_cast<int>(id));
    }
    for (std::size_t k = 1; k + 1 < ids.size(); ++k)
      mesh.triangles.emplace_back(ids[0], ids[k], ids[k + 1]);
  }
  return mesh;
}

Result<MeshData> readOff(const std::string& path) {
  std::ifstream file(path, std::ios::binary);
  if (!file) return Status(ErrorCode::File, "cannot open " + path);
  std::ostringstream text;
  text << file.rdbuf();
  if (file.bad()) return Status(ErrorCode::File, "cannot read " + path);
  return parseOff(text.str());
}

MeshData readOffOrEmpty(const std::string& path) {
  Result<MeshData> mesh = readOff(path);
  if (mesh.ok()) return std::move(mesh.value());
  std::fprintf(stderr, "cannot read %s: %s\n", path.c_str(), mesh.status().message().c_str());
  return {};
}

MeshData fitToSize(MeshData mesh, double size) {
  if (mesh.vertices.empty()) return mesh;
  Aabb box;
  for (const Vec3& v : mesh.vertices) box.extend(v);
  const double extent = (box.max - box.min).maxCoeff();
  const Vec3 centre = 0.5 * (box.min + box.max);
  const double scale = size / (extent > 0 ? extent : 1.0);
  for (Vec3& v : mesh.vertices) v = (v - centre) * scale;
  return mesh;
}

}  // namespace sc::support
