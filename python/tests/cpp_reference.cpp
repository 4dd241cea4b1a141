// SPDX-License-Identifier: MIT
// The C++ side of the Python tests' comparison: reads two meshes, settings and a
// sequence of pose pairs (text, stdin), runs sc::PairTracker on both directions
// exactly as the module does, and prints every result field and contact with 17
// significant digits, one line per direction and pose.
#include <cstdio>
#include <cstdlib>
#include <iostream>
#include <memory>
#include <string>
#include <vector>

#include "smartcollision/smartcollision.h"

namespace {

/// The next token as a number; strtod also reads "inf" and "nan".
double num() {
  std::string token;
  std::cin >> token;
  return std::strtod(token.c_str(), nullptr);
}

sc::ModelPtr readModel(sc::ModelKind kind) {
  std::string word;
  size_t nv = 0, nf = 0;
  std::cin >> word >> nv >> nf;
  sc::MeshData mesh;
  mesh.vertices.resize(nv);
  mesh.triangles.resize(nf);
  for (sc::Vec3& v : mesh.vertices) v = {num(), num(), num()};
  for (sc::Tri& t : mesh.triangles) std::cin >> t.x() >> t.y() >> t.z();
  sc::Result<sc::PiecePtr> piece = sc::buildPiece(kind, mesh);
  if (!piece.ok()) {
    std::fprintf(stderr, "%s\n", piece.status().message().c_str());
    std::exit(1);
  }
  return std::make_shared<const sc::Model>(kind, std::vector<sc::PiecePtr>{piece.value()});
}

sc::Vec3 readVec3() {
  const double x = num(), y = num();
  return {x, y, num()};
}

/// As the module: centre kept, orientation normalised, then the origin placed.
sc::Placement readPlacement(const sc::Vec3& local_center) {
  const sc::Vec3 origin = readVec3();
  const double w = num(), x = num(), y = num(), z = num();
  sc::Placement p;
  p.local_center = local_center;
  p.setOrientation(sc::Quat(w, x, y, z));
  p.setOrigin(origin);
  return p;
}

void print(const double* v, int n) {
  for (int i = 0; i < n; ++i) std::printf(" %.17g", v[i]);
}

void printFeature(const sc::Feature& f) {
  std::printf(" %d %d %d %d %d", static_cast<int>(f.type), f.vertices[0], f.vertices[1],
              f.vertices[2], f.is_virtual ? 1 : 0);
}

void printResult(const sc::DirectedResult& r, const std::vector<sc::ContactPoint>& contacts) {
  std::printf("%d", static_cast<int>(r.code));
  print(&r.distance, 1);
  for (const sc::Vec3* v : {&r.normal, &r.point_on_target, &r.point_on_opponent, &r.tpdv, &r.rpdv,
                            &r.contact_position}) {
    print(v->data(), 3);
  }
  const double q[4] = {r.contact_orientation.w(), r.contact_orientation.x(),
                       r.contact_orientation.y(), r.contact_orientation.z()};
  print(q, 4);
  std::printf(" %d %d %d %d", r.target_object, r.opponent_object, r.target_piece, r.opponent_piece);
  printFeature(r.target_feature);
  printFeature(r.opponent_feature);
  std::printf(" %zu", contacts.size());
  for (const sc::ContactPoint& c : contacts) {
    print(c.point_on_target.data(), 3);
    print(c.point_on_opponent.data(), 3);
    print(c.normal.data(), 3);
    print(&c.separation, 1);
    std::printf(" %d %d %d %d", c.target_object, c.opponent_object, c.target_piece,
                c.opponent_piece);
  }
  std::printf("\n");
}

}  // namespace

int main() {
  std::string word;
  int kind = 0, mode = 0, resolve = 0;
  sc::SceneSettings settings;
  std::cin >> word >> kind >> word;
  settings.tolerance = num();
  std::cin >> mode >> settings.max_iterations >> resolve;
  settings.max_distance = num();
  settings.rotation_mode = static_cast<sc::RotationMode>(mode);
  settings.resolve_initial_intersection = resolve != 0;
  std::cin >> word;
  const sc::Vec3 center_a = readVec3();
  std::cin >> word;
  const sc::Vec3 center_b = readVec3();
  const sc::ModelPtr a = readModel(static_cast<sc::ModelKind>(kind));
  const sc::ModelPtr b = readModel(static_cast<sc::ModelKind>(kind));
  const sc::Part parts[2] = {{a.get(), sc::Rigid(), 0}, {b.get(), sc::Rigid(), 1}};
  int poses = 0;
  std::cin >> word >> poses;
  sc::PairTracker tracker;
  sc::DirectedResult out[2];
  std::vector<sc::ContactPoint> contacts;
  for (int i = 0; i < poses && std::cin; ++i) {
    const sc::GroupView ga{&parts[0], 1, readPlacement(center_a)};
    const sc::GroupView gb{&parts[1], 1, readPlacement(center_b)};
    tracker.update(ga, gb, {true, true}, settings, out);
    for (int d = 0; d < 2; ++d) {
      tracker.contactPoints(d, settings.tolerance, contacts);
      printResult(out[d], contacts);
    }
  }
  return std::cin ? 0 : 1;
}
