// SPDX-License-Identifier: MIT
// Convex surface decomposition on small analytic shapes built from unit voxels:
// a cube, an L-shaped prism, a cube with a box-shaped dent and a ring of boxes;
// the patch polytope builder on hand-picked flat patches; and the OFF reader the
// decomposition's mesh tests load CGAL's meshes with.
#include "preprocess/convex_decomposition.h"

#include "geometry/triangle_adjacency.h"
#include "preprocess/patch_growth.h"
#include "preprocess/patch_polytope.h"

#include <gtest/gtest.h>

#include <algorithm>
#include <array>
#include <cmath>
#include <map>
#include <set>
#include <tuple>
#include <vector>

#include "sc_support/off_mesh.h"
#include "sc_support/sample_meshes.h"
#include "support/shapes.h"
#include "support/test_support.h"

namespace sc::detail {
namespace {

using Cell = std::array<int, 3>;

/// The closed, outward surface of a union of unit voxels; every voxel face is cut
/// into `split` x `split` squares of two triangles, so flat regions are made of
/// many coplanar triangles. The voxels must meet along whole faces only.
MeshData voxelMesh(const std::set<Cell>& cells, int split) {
  MeshData mesh;
  std::map<std::tuple<int, int, int>, int> index;
  auto vertex = [&](int x, int y, int z) {
    const auto key = std::make_tuple(x, y, z);
    const auto it = index.find(key);
    if (it != index.end()) return it->second;
    const int id = static_cast<int>(mesh.vertices.size());
    mesh.vertices.emplace_back(static_cast<double>(x) / split, static_cast<double>(y) / split,
                               static_cast<double>(z) / split);
    index.emplace(key, id);
    return id;
  };
  auto triangle = [&](int a, int b, int c, const Vec3& outward) {
    const Vec3 n = (mesh.vertices[b] - mesh.vertices[a]).cross(mesh.vertices[c] - mesh.vertices[a]);
    if (n.dot(outward) > 0.0) {
      mesh.triangles.emplace_back(a, b, c);
    } else {
      mesh.triangles.emplace_back(a, c, b);
    }
  };
  for (const Cell& c : cells) {
    for (int axis = 0; axis < 3; ++axis) {
      for (int side = 0; side < 2; ++side) {
        Cell neighbour = c;
        neighbour[axis] += side == 0 ? -1 : 1;
        if (cells.count(neighbour)) continue;
        Vec3 outward = Vec3::Zero();
        outward[axis] = side == 0 ? -1.0 : 1.0;
        const int u = (axis + 1) % 3, v = (axis + 2) % 3;
        for (int i = 0; i < split; ++i) {
          for (int j = 0; j < split; ++j) {
            int corner[4][3];
            for (int k = 0; k < 4; ++k) {
              corner[k][axis] = (c[axis] + side) * split;
              corner[k][u] = c[u] * split + i + (k == 1 || k == 2 ? 1 : 0);
              corner[k][v] = c[v] * split + j + (k >= 2 ? 1 : 0);
            }
            int id[4];
            for (int k = 0; k < 4; ++k) id[k] = vertex(corner[k][0], corner[k][1], corner[k][2]);
            triangle(id[0], id[1], id[2], outward);
            triangle(id[0], id[2], id[3], outward);
          }
        }
      }
    }
  }
  return mesh;
}

std::set<Cell> box(int nx, int ny, int nz) {
  std::set<Cell> cells;
  for (int x = 0; x < nx; ++x) {
    for (int y = 0; y < ny; ++y) {
      for (int z = 0; z < nz; ++z) cells.insert({x, y, z});
    }
  }
  return cells;
}

/// Candidate separating axes of a convex polytope and boxes: its face normals,
/// the box axes, and cross products of its edges with the box axes; unit, with
/// duplicates (coplanar faces, parallel edges) removed.
std::vector<Vec3> separatingAxes(const ConvexPolytope& hull) {
  std::vector<Vec3> axes = {Vec3::UnitX(), Vec3::UnitY(), Vec3::UnitZ()};
  auto add = [&](const Vec3& v) {
    if (v.norm() <= 1e-12) return;
    Vec3 a = v.normalized();
    // One sign per direction: the first clearly non-zero component positive.
    for (int k = 0; k < 3; ++k) {
      if (std::abs(a[k]) > 1e-9) {
        if (a[k] < 0) a = -a;
        break;
      }
    }
    axes.push_back(a);
  };
  for (const Tri& f : hull.faces) {
    const Vec3& a = hull.vertices[f[0]];
    add((hull.vertices[f[1]] - a).cross(hull.vertices[f[2]] - a));
    for (int k = 0; k < 3; ++k) {
      const Vec3 edge = hull.vertices[f[(k + 1) % 3]] - hull.vertices[f[k]];
      for (int axis = 0; axis < 3; ++axis) add(edge.cross(Vec3::Unit(axis)));
    }
  }
  std::sort(axes.begin(), axes.end(), [](const Vec3& a, const Vec3& b) {
    return std::lexicographical_compare(a.data(), a.data() + 3, b.data(), b.data() + 3);
  });
  axes.erase(std::unique(axes.begin(), axes.end(),
                         [](const Vec3& a, const Vec3& b) { return (a - b).norm() < 1e-12; }),
             axes.end());
  return axes;
}

/// Penetration depth of a convex polytope and a box by the separating axis
/// theorem: the smallest overlap over `axes` (from separatingAxes); <= 0 when
/// they are disjoint or touch.
double penetration(const ConvexPolytope& hull, const std::vector<Vec3>& axes, const Aabb& cell) {
  const Vec3 centre = 0.5 * (cell.min + cell.max), half = 0.5 * (cell.max - cell.min);
  double depth = kInfinity;
  for (const Vec3& a : axes) {
    double lo = kInfinity, hi = -kInfinity;
    for (const Vec3& p : hull.vertices) {
      lo = std::min(lo, a.dot(p));
      hi = std::max(hi, a.dot(p));
    }
    const double c = a.dot(centre), r = a.cwiseAbs().dot(half);
    depth = std::min(depth, std::min(hi, c + r) - std::max(lo, c - r));
  }
  return depth;
}

/// Structural invariants every decomposition must satisfy, plus: no hull
/// overlaps an empty voxel, which for a voxel shape is exactly "every hull lies
/// inside the solid".
void expectValidDecomposition(const MeshData& mesh, const std::set<Cell>& cells,
                              const Decomposition& d) {
  const int n = static_cast<int>(mesh.triangles.size());
  ASSERT_EQ(d.triangle_patch.size(), mesh.triangles.size());
  auto rotated = [](int a, int b, int c) {
    std::array<int, 3> k = {a, b, c};
    std::rotate(k.begin(), std::min_element(k.begin(), k.end()), k.end());
    return k;
  };
  std::set<std::array<int, 3>> inputs;
  for (const Tri& t : mesh.triangles) inputs.insert(rotated(t[0], t[1], t[2]));
  std::vector<int> seen(n, 0);
  int virtual_faces = 0;
  for (std::size_t p = 0; p < d.patches.size(); ++p) {
    SCOPED_TRACE("patch " + std::to_string(p));
    const ConvexPolytope& poly = d.patches[p];
    ASSERT_EQ(poly.vertices.size(), poly.original.size());
    ASSERT_EQ(poly.faces.size(), poly.face_source.size());
    for (std::size_t i = 0; i < poly.vertices.size(); ++i) {
      EXPECT_EQ(poly.vertices[i], mesh.vertices[poly.original[i]]);
    }
    std::map<std::pair<int, int>, int> directed;
    for (std::size_t f = 0; f < poly.faces.size(); ++f) {
      const Tri& face = poly.faces[f];
      for (int k = 0; k < 3; ++k) ++directed[{face[k], face[(k + 1) % 3]}];
      // Every face is a hull face: all vertices on or below its plane.
      const Vec3& a = poly.vertices[face[0]];
      const Vec3 normal = (poly.vertices[face[1]] - a).cross(poly.vertices[face[2]] - a);
      ASSERT_GT(normal.norm(), 1e-12);
      for (const Vec3& q : poly.vertices) EXPECT_LE(normal.normalized().dot(q - a), 1e-12);
      const int source = poly.face_source[f];
      const std::array<int, 3> corners =
          rotated(poly.original[face[0]], poly.original[face[1]], poly.original[face[2]]);
      if (source < 0) {
        ++virtual_faces;
        EXPECT_EQ(inputs.count(corners), 0u) << "virtual face " << f << " is an input triangle";
        continue;
      }
      ASSERT_LT(source, n);
      const Tri& t = mesh.triangles[source];
      EXPECT_TRUE(corners == rotated(t[0], t[1], t[2]));
      // A hull face may equal a triangle of another patch: still a model face.
      if (d.triangle_patch[source] == static_cast<int>(p)) ++seen[source];
    }
    // A closed, consistently oriented surface: each edge used as often in each
    // direction. A flat patch is a double-sided polygon, where an edge may bound
    // one face on each side in each direction.
    for (const auto& [edge, uses] : directed) {
      EXPECT_LE(uses, 2);
      const auto reverse = directed.find({edge.second, edge.first});
      ASSERT_TRUE(reverse != directed.end());
      EXPECT_EQ(reverse->second, uses);
    }
    // Every empty voxel the hull's box touches (voxels beyond it cannot overlap).
    const std::vector<Vec3> axes = separatingAxes(poly);
    const Vec3 lo = poly.bounds().min.array().floor(), hi = poly.bounds().max.array().ceil();
    for (int x = static_cast<int>(lo.x()); x < static_cast<int>(hi.x()); ++x) {
      for (int y = static_cast<int>(lo.y()); y < static_cast<int>(hi.y()); ++y) {
        for (int z = static_cast<int>(lo.z()); z < static_cast<int>(hi.z()); ++z) {
          if (cells.count({x, y, z})) continue;
          Aabb empty;
          empty.extend(Vec3(x, y, z));
          empty.extend(Vec3(x + 1, y + 1, z + 1));
          EXPECT_LE(penetration(poly, axes, empty), 1e-9)
              << "hull overlaps empty voxel " << x << " " << y << " " << z;
        }
      }
    }
  }
  // The patches partition the triangles: each is a real face of its own patch once.
  for (int t = 0; t < n; ++t) EXPECT_EQ(seen[t], 1) << "triangle " << t;
  EXPECT_EQ(virtual_faces, d.virtual_faces);
}

Decomposition decompose(const MeshData& mesh) {
  Result<Decomposition> d = decomposeConvexSurface(mesh, {});
  EXPECT_TRUE(d.ok()) << d.status().message();
  return d.ok() ? d.value() : Decomposition{};
}

TEST(ConvexDecomposition, CubeIsOnePatchWithoutVirtualFaces) {
  const std::set<Cell> cells = box(2, 2, 2);  // 4 coplanar triangles per face quarter
  const MeshData mesh = voxelMesh(cells, 1);
  const Decomposition d = decompose(mesh);
  ASSERT_EQ(d.patches.size(), 1u);
  EXPECT_EQ(d.virtual_faces, 0);
  // qhull keeps only the 8 corners; the patch keeps all 26 surface grid points
  // and its own 48 triangles, including the flat ones qhull would triangulate
  // differently.
  EXPECT_EQ(d.patches[0].vertices.size(), 26u);
  EXPECT_EQ(d.patches[0].faces.size(), 48u);
  expectValidDecomposition(mesh, cells, d);
}

TEST(ConvexDecomposition, TetrahedronIsOnePatch) {
  const MeshData mesh = test::regularTetrahedronMesh(1.0);
  const Decomposition d = decompose(mesh);
  ASSERT_EQ(d.patches.size(), 1u);
  EXPECT_EQ(d.virtual_faces, 0);
  EXPECT_EQ(d.patches[0].faces.size(), 4u);
}

TEST(ConvexDecomposition, LShapedPrismNeedsTwoPatchesOrMore) {
  // The top and bottom L faces are not convex: no single hull covers either.
  const std::set<Cell> cells = {{0, 0, 0}, {1, 0, 0}, {0, 1, 0}};
  for (int split : {1, 2}) {
    SCOPED_TRACE("split " + std::to_string(split));
    const MeshData mesh = voxelMesh(cells, split);
    const Decomposition d = decompose(mesh);
    EXPECT_GE(d.patches.size(), 2u);
    EXPECT_GT(d.virtual_faces, 0);
    expectValidDecomposition(mesh, cells, d);
  }
}

TEST(ConvexDecomposition, CubeWithBoxDentKeepsHullsOutOfTheDent) {
  std::set<Cell> cells = box(3, 3, 3);
  cells.erase({1, 1, 2});  // the dent: one voxel deep, open at the top
  for (int split : {1, 2}) {
    SCOPED_TRACE("split " + std::to_string(split));
    const MeshData mesh = voxelMesh(cells, split);
    const Decomposition d = decompose(mesh);
    // The top face is a square ring around the dent's opening; a convex piece of
    // it must stay on one side of a line past the opening, and no three such
    // half-planes cover a ring around a square.
    EXPECT_GE(d.patches.size(), 4u);
    expectValidDecomposition(mesh, cells, d);
  }
}

TEST(ConvexDecomposition, RingOfBoxesKeepsHullsOutOfTheHole) {
  std::set<Cell> cells = box(3, 3, 1);
  cells.erase({1, 1, 0});  // torus-like: eight boxes around a square hole
  for (int split : {1, 2}) {
    SCOPED_TRACE("split " + std::to_string(split));
    const MeshData mesh = voxelMesh(cells, split);
    const Decomposition d = decompose(mesh);
    EXPECT_GE(d.patches.size(), 4u);  // as for the dent: top and bottom are rings
    expectValidDecomposition(mesh, cells, d);
  }
}

TEST(ConvexDecomposition, OpenSurfaceIsInvalidGeometry) {
  MeshData mesh = voxelMesh(box(1, 1, 1), 1);
  mesh.triangles.pop_back();
  const Result<Decomposition> d = decomposeConvexSurface(mesh, {});
  ASSERT_FALSE(d.ok());
  EXPECT_EQ(d.status().code(), ErrorCode::InvalidGeometry);
}

TEST(ConvexDecomposition, ReportsProgressUpToOne) {
  std::set<Cell> cells = box(3, 3, 1);
  cells.erase({1, 1, 0});
  const MeshData mesh = voxelMesh(cells, 2);
  std::vector<double> fractions;
  const Result<Decomposition> d =
      decomposeConvexSurface(mesh, [&](double fraction, const char* stage) {
        EXPECT_STREQ(stage, "decompose");
        fractions.push_back(fraction);
      });
  ASSERT_TRUE(d.ok());
  ASSERT_GE(fractions.size(), 2u);
  EXPECT_TRUE(std::is_sorted(fractions.begin(), fractions.end()));
  EXPECT_EQ(fractions.front(), 0.0);
  EXPECT_EQ(fractions.back(), 1.0);
}

/// The triangles of `mesh` whose three vertices have z == top (within 1e-12).
std::vector<int> topTriangles(const MeshData& mesh, double top) {
  std::vector<int> faces;
  for (int t = 0; t < static_cast<int>(mesh.triangles.size()); ++t) {
    bool on_top = true;
    for (int k = 0; k < 3; ++k)
      on_top = on_top && std::abs(mesh.vertices[mesh.triangles[t][k]].z() - top) < 1e-12;
    if (on_top) faces.push_back(t);
  }
  return faces;
}

Result<PatchPolytope> polytopeOf(const MeshData& mesh, const std::vector<int>& faces) {
  const TriangleAdjacency adjacency = TriangleAdjacency::build(mesh).value();
  std::vector<int> rank(mesh.triangles.size(), -1);
  for (int i = 0; i < static_cast<int>(faces.size()); ++i) rank[faces[i]] = i;
  const PatchRef patch{faces, rank, static_cast<int>(faces.size())};
  return buildPatchPolytope(mesh, adjacency, patch, decompositionTolerance(mesh));
}

TEST(PatchPolytope, FlatLFaceWhosePocketOverhangsANotchIsRejected) {
  // The L's top face: its hull polygon covers the notch, where the solid drops.
  const MeshData mesh = voxelMesh({{0, 0, 0}, {1, 0, 0}, {0, 1, 0}}, 1);
  const std::vector<int> top = topTriangles(mesh, 1.0);
  ASSERT_EQ(top.size(), 6u);
  const Result<PatchPolytope> poly = polytopeOf(mesh, top);
  ASSERT_FALSE(poly.ok());
  EXPECT_EQ(poly.status().code(), ErrorCode::InvalidGeometry);
}

TEST(PatchPolytope, FlatPocketOverCoplanarTrianglesIsAcceptedAsRealHull) {
  // Three of the four top squares of a 2 x 2 x 1 box: the pocket lies on the
  // fourth square, on the surface.
  const MeshData mesh = voxelMesh(box(2, 2, 1), 1);
  std::vector<int> top = topTriangles(mesh, 1.0);
  ASSERT_EQ(top.size(), 8u);
  std::vector<int> patch;
  for (int t : top) {
    Vec3 centre = Vec3::Zero();
    for (int k = 0; k < 3; ++k) centre += mesh.vertices[mesh.triangles[t][k]] / 3.0;
    if (!(centre.x() > 1.0 && centre.y() > 1.0)) patch.push_back(t);
  }
  ASSERT_EQ(patch.size(), 6u);
  const Result<PatchPolytope> poly = polytopeOf(mesh, patch);
  ASSERT_TRUE(poly.ok()) << poly.status().message();
  EXPECT_TRUE(poly.value().flat);
  // Front: 6 patch triangles and the pocket (the missing square's corner
  // triangle, 1 face); back: the hull polygon (square with 3 collinear extra
  // points, 7 vertices) in 5 triangles.
  EXPECT_EQ(poly.value().virtual_faces, 1 + 5);
  double front = 0.0, back = 0.0;
  const ConvexPolytope& hull = poly.value().polytope;
  for (const Tri& f : hull.faces) {
    const double signed_area = 0.5 * (hull.vertices[f[1]] - hull.vertices[f[0]])
                                         .cross(hull.vertices[f[2]] - hull.vertices[f[0]])
                                         .z();
    (signed_area > 0 ? front : back) += std::abs(signed_area);
  }
  EXPECT_NEAR(front, 3.5, 1e-12);  // three squares and half of the fourth
  EXPECT_NEAR(back, 3.5, 1e-12);
}

/// A unit cube whose top quad is bent along its diagonal by moving the corner off
/// the diagonal by `dz` tolerances: down makes a convex fold, up a concave one.
MeshData bentCube(double dz, std::vector<int>& top) {
  MeshData mesh = voxelMesh(box(1, 1, 1), 1);
  top = topTriangles(mesh, 1.0);
  const Tri& t0 = mesh.triangles[top.at(0)];
  const Tri& t1 = mesh.triangles[top.at(1)];
  for (int k = 0; k < 3; ++k) {
    if (t0[k] != t1[0] && t0[k] != t1[1] && t0[k] != t1[2]) {
      mesh.vertices[t0[k]].z() += dz * decompositionTolerance(mesh);
    }
  }
  return mesh;
}

TEST(PatchPolytope, NearlyFlatConvexFoldTakesTheHullsBackDiagonal) {
  // Folded down by 1.5 tolerances (still flat within kFlatFactor): back faces on
  // the fold's diagonal would not support the points; the hull's use the other.
  std::vector<int> top;
  const MeshData mesh = bentCube(-1.5, top);
  ASSERT_EQ(top.size(), 2u);
  const Result<PatchPolytope> poly = polytopeOf(mesh, top);
  ASSERT_TRUE(poly.ok()) << poly.status().message();
  EXPECT_TRUE(poly.value().flat);
  const ConvexPolytope& hull = poly.value().polytope;
  ASSERT_EQ(hull.faces.size(), 4u);
  for (const Tri& f : hull.faces) {
    const Vec3 n = (hull.vertices[f[1]] - hull.vertices[f[0]])
                       .cross(hull.vertices[f[2]] - hull.vertices[f[0]])
                       .normalized();
    for (const Vec3& q : hull.vertices) EXPECT_LE(n.dot(q - hull.vertices[f[0]]), 1e-15);
  }
}

TEST(PatchPolytope, ConcaveFoldBeyondTheToleranceIsRejected) {
  std::vector<int> top;
  const MeshData mesh = bentCube(1.5, top);
  const Result<PatchPolytope> poly = polytopeOf(mesh, top);
  EXPECT_FALSE(poly.ok());
}

TEST(OffReader, ReadsVerticesAndSplitsPolygonsIntoFans) {
  const Result<MeshData> mesh = support::parseOff(
      "OFF\n# a comment\n5 2 0\n0 0 0\n1 0 0\n1 1 0\n0 1 0\n0 0 1\n"
      "4 0 1 2 3\n3 0 1 4 255 0 0\n");
  ASSERT_TRUE(mesh.ok()) << mesh.status().message();
  ASSERT_EQ(mesh.value().vertices.size(), 5u);
  EXPECT_EQ(mesh.value().vertices[2], Vec3(1, 1, 0));
  ASSERT_EQ(mesh.value().triangles.size(), 3u);
  EXPECT_EQ(mesh.value().triangles[0], Tri(0, 1, 2));
  EXPECT_EQ(mesh.value().triangles[1], Tri(0, 2, 3));
  EXPECT_EQ(mesh.value().triangles[2], Tri(0, 1, 4));  // the colour is ignored
}

TEST(OffReader, RejectsMalformedFiles) {
  const char* bad[] = {
      "",                                              // empty
      "PLY\n3 1 0\n0 0 0\n1 0 0\n0 1 0\n3 0 1 2\n",    // wrong header
      "OFF\n3 1 0\n0 0 0\n1 0 0\n",                    // ends early
      "OFF\n3 1 0\n0 0 0\n1 x 0\n0 1 0\n3 0 1 2\n",    // not a number
      "OFF\n3 1 0\n0 0 0\n1 0 0\n0 1 0\n3 0 1 3\n",    // index out of range
      "OFF\n3 1 0\n0 0 0\n1 0 0\n0 1 0\n2 0 1\n",      // two corners
      "OFF\n3 1 0\n0 0 0\n1 0 0\n0 1 0\n3 0 1\n",      // missing index
      "OFF\n3 1 0\n0 0 0\n1 0 0\n0 1 inf\n3 0 1 2\n",  // not finite
      "OFF\n-3 1 0\n",                                 // negative count
  };
  for (const char* text : bad) {
    const Result<MeshData> mesh = support::parseOff(text);
    EXPECT_FALSE(mesh.ok()) << text;
    EXPECT_EQ(mesh.status().code(), ErrorCode::InvalidArgument) << text;
  }
  const Result<MeshData> missing = support::readOff("/nonexistent/mesh.off");
  ASSERT_FALSE(missing.ok());
  EXPECT_EQ(missing.status().code(), ErrorCode::File);
}

// Patches stop growing at kMaxPatchTriangles (large patches that keep failing their
// checks made the cost per triangle grow with the mesh), and the capped patches still
// partition the surface; a convex piece stays one patch whatever its size.
TEST(ConvexDecomposition, PatchesStopAtTheCapAndStillPartitionTheSurface) {
  const MeshData torus = samples::torusMesh(1.0, 0.3, 150, 75);
  const Decomposition d = decompose(torus);
  std::vector<int> size(d.patches.size(), 0);
  for (int p : d.triangle_patch) ++size[static_cast<std::size_t>(p)];
  const int largest = *std::max_element(size.begin(), size.end());
  EXPECT_LE(largest, kMaxPatchTriangles);
  EXPECT_GE(largest, kMaxPatchTriangles / 2);  // the convex band's patches reach it
  std::vector<int> seen(torus.triangles.size(), 0);
  for (std::size_t p = 0; p < d.patches.size(); ++p) {
    // A hull face may equal a triangle of another patch: counted there.
    for (int t : d.patches[p].face_source) {
      if (t >= 0 && d.triangle_patch[static_cast<std::size_t>(t)] == static_cast<int>(p))
        ++seen[static_cast<std::size_t>(t)];
    }
  }
  for (std::size_t t = 0; t < seen.size(); ++t) EXPECT_EQ(seen[t], 1) << "triangle " << t;

  test::Rng rng(5);
  std::vector<Vec3> on_sphere;
  for (int i = 0; i < 600; ++i) on_sphere.push_back(test::randomDirection(rng));
  const MeshData ball = test::meshOf(test::hullOf(on_sphere));
  ASSERT_GT(ball.triangles.size(), 2u * kMaxPatchTriangles);
  EXPECT_EQ(decompose(ball).patches.size(), 1u);
}

}  // namespace
}  // namespace sc::detail
