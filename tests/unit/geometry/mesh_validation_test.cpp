// SPDX-License-Identifier: MIT
// Unit tests of the piece input checks: one test per class of bad input, the
// orientation fix, and the convexity test on hand-made solids.
#include "geometry/mesh_validation.h"

#include <gtest/gtest.h>

#include <cmath>
#include <cstdint>
#include <limits>
#include <map>
#include <string>
#include <tuple>
#include <vector>

#include "support/test_support.h"

namespace sc::detail {
namespace {

using Cell = Eigen::Vector3i;

/// The manual's tetrahedron (List 6-2 and the sample code): outward winding.
MeshData tetrahedron() {
  return {{{0, 0, 0}, {1, 0, 0}, {0, 1, 0}, {0, 0, 1}}, {{0, 2, 1}, {1, 3, 0}, {0, 3, 2}, {1, 2, 3}}};
}

MeshData octahedron() {
  MeshData m;
  m.vertices = {{1, 0, 0}, {-1, 0, 0}, {0, 1, 0}, {0, -1, 0}, {0, 0, 1}, {0, 0, -1}};
  // Each face spans one octant; wind it so its normal points into that octant.
  for (int sx : {0, 1}) {
    for (int sy : {2, 3}) {
      for (int sz : {4, 5}) {
        const int flips = (sx == 1) + (sy == 3) + (sz == 5);
        m.triangles.push_back(flips % 2 == 0 ? Tri(sx, sy, sz) : Tri(sx, sz, sy));
      }
    }
  }
  return m;
}

/// Boundary of a union of unit voxels, outward. With `split_faces` each boundary
/// square gets a centre vertex and four coplanar triangles, else two triangles.
MeshData voxelMesh(const std::vector<Cell>& cells, bool split_faces = false) {
  MeshData m;
  std::map<std::tuple<int, int, int>, int> index;  // doubled coordinates -> vertex
  auto vertex = [&](const Vec3& p) {
    const auto key = std::make_tuple(int(std::lround(2 * p.x())), int(std::lround(2 * p.y())),
                                     int(std::lround(2 * p.z())));
    const auto [it, inserted] = index.emplace(key, static_cast<int>(m.vertices.size()));
    if (inserted) m.vertices.push_back(p);
    return it->second;
  };
  auto occupied = [&](const Cell& c) {
    for (const Cell& d : cells) {
      if (d == c) return true;
    }
    return false;
  };
  for (const Cell& c : cells) {
    for (int axis = 0; axis < 3; ++axis) {
      for (int side : {-1, 1}) {
        if (occupied(c + side * Cell::Unit(axis))) continue;
        const Vec3 u = Vec3::Unit((axis + 1) % 3), w = Vec3::Unit((axis + 2) % 3);
        Vec3 base = c.cast<double>();
        if (side > 0) base += Vec3::Unit(axis);
        // u x w = +axis: this order is counter-clockwise seen from the +axis side.
        std::vector<Vec3> quad = {base, base + u, base + u + w, base + w};
        if (side < 0) std::swap(quad[1], quad[3]);
        int q[4];
        for (int k = 0; k < 4; ++k) q[k] = vertex(quad[k]);
        if (split_faces) {
          const int mid = vertex(base + 0.5 * (u + w));
          for (int k = 0; k < 4; ++k) m.triangles.emplace_back(q[k], q[(k + 1) % 4], mid);
        } else {
          m.triangles.emplace_back(q[0], q[1], q[2]);
          m.triangles.emplace_back(q[0], q[2], q[3]);
        }
      }
    }
  }
  return m;
}

MeshData cube() { return voxelMesh({Cell(0, 0, 0)}); }

/// A five-pointed star extruded along z: closed, star-shaped, not convex.
MeshData starPrism() {
  MeshData m;
  const int n = 10;
  for (int i = 0; i < n; ++i) {
    const double angle = 2.0 * M_PI * i / n, r = i % 2 == 0 ? 1.0 : 0.4;
    m.vertices.emplace_back(r * std::cos(angle), r * std::sin(angle), 0.0);
    m.vertices.emplace_back(r * std::cos(angle), r * std::sin(angle), 1.0);
  }
  const int bottom = 2 * n, top = 2 * n + 1;
  m.vertices.emplace_back(0, 0, 0);
  m.vertices.emplace_back(0, 0, 1);
  for (int i = 0; i < n; ++i) {
    const int j = (i + 1) % n;
    m.triangles.emplace_back(top, 2 * i + 1, 2 * j + 1);
    m.triangles.emplace_back(bottom, 2 * j, 2 * i);
    m.triangles.emplace_back(2 * i, 2 * j, 2 * j + 1);
    m.triangles.emplace_back(2 * i, 2 * j + 1, 2 * i + 1);
  }
  return m;
}

/// Two meshes as one piece. With glue >= 0 the second mesh's vertex 0 becomes the
/// first mesh's vertex `glue`.
MeshData join(const MeshData& a, const MeshData& b, int glue = -1) {
  MeshData m = a;
  const int offset = static_cast<int>(a.vertices.size()) - (glue >= 0 ? 1 : 0);
  for (std::size_t i = glue >= 0 ? 1 : 0; i < b.vertices.size(); ++i) m.vertices.push_back(b.vertices[i]);
  for (const Tri& t : b.triangles) {
    Tri s;
    for (int k = 0; k < 3; ++k) s[k] = glue >= 0 && t[k] == 0 ? glue : t[k] + offset;
    m.triangles.push_back(s);
  }
  return m;
}

MeshData translated(MeshData m, const Vec3& d) {
  for (Vec3& v : m.vertices) v += d;
  return m;
}

MeshData reversed(MeshData m) {
  for (Tri& t : m.triangles) std::swap(t[1], t[2]);
  return m;
}

/// Signed volume by the divergence theorem, straight from the definition.
double signedVolume(const MeshData& m) {
  double v = 0.0;
  for (const Tri& t : m.triangles) {
    v += m.vertices[t[0]].dot(m.vertices[t[1]].cross(m.vertices[t[2]])) / 6.0;
  }
  return v;
}

/// validateClosed on a copy; expects InvalidGeometry, an unchanged mesh and a
/// message containing `where`.
void expectInvalidGeometry(const MeshData& mesh, const std::string& where) {
  ASSERT_TRUE(validateArrays(mesh).ok()) << validateArrays(mesh).message();
  MeshData copy = mesh;
  bool flipped = true;
  const Status s = validateClosed(copy, flipped);
  EXPECT_EQ(s.code(), ErrorCode::InvalidGeometry) << s.message();
  EXPECT_NE(s.message().find(where), std::string::npos) << s.message();
  EXPECT_FALSE(flipped);
  EXPECT_EQ(copy.triangles, mesh.triangles);
}

void expectValidUnflipped(const MeshData& mesh) {
  ASSERT_TRUE(validateArrays(mesh).ok()) << validateArrays(mesh).message();
  MeshData copy = mesh;
  bool flipped = true;
  const Status s = validateClosed(copy, flipped);
  EXPECT_TRUE(s.ok()) << s.message();
  EXPECT_FALSE(flipped);
  EXPECT_EQ(copy.triangles, mesh.triangles);
  EXPECT_GT(signedVolume(copy), 0.0);
}

// --- validateArrays -------------------------------------------------------------

TEST(ValidateArrays, NanCoordinateIsInvalidArgument) {
  MeshData m = tetrahedron();
  m.vertices[2].y() = std::numeric_limits<double>::quiet_NaN();
  const Status s = validateArrays(m);
  EXPECT_EQ(s.code(), ErrorCode::InvalidArgument);
  EXPECT_NE(s.message().find("vertex 2"), std::string::npos) << s.message();
}

TEST(ValidateArrays, InfiniteCoordinateIsInvalidArgument) {
  // Runs with FE_INVALID trapped: the check itself must not compute inf - inf.
  for (const double bad : {kInfinity, -kInfinity}) {
    MeshData m = tetrahedron();
    m.vertices[3].z() = bad;
    const Status s = validateArrays(m);
    EXPECT_EQ(s.code(), ErrorCode::InvalidArgument);
    EXPECT_NE(s.message().find("vertex 3"), std::string::npos) << s.message();
  }
}

TEST(ValidateArrays, NonFiniteUnusedVertexIsStillInvalidArgument) {
  MeshData m = tetrahedron();
  m.vertices.emplace_back(std::numeric_limits<double>::quiet_NaN(), 0.0, 0.0);
  EXPECT_EQ(validateArrays(m).code(), ErrorCode::InvalidArgument);
}

/// The tetrahedron with vertex index `index` at corner `corner` of triangle `t`: an
/// InvalidArgument that names the triangle.
void expectBadIndex(int t, int corner, int index) {
  MeshData m = tetrahedron();
  m.triangles[static_cast<std::size_t>(t)][corner] = index;
  const Status s = validateArrays(m);
  EXPECT_EQ(s.code(), ErrorCode::InvalidArgument) << "index " << index;
  EXPECT_NE(s.message().find("triangle " + std::to_string(t)), std::string::npos) << s.message();
}

TEST(ValidateArrays, IndexOutOfRangeIsInvalidArgument) {
  expectBadIndex(1, 2, 4);  // == vertex count
  expectBadIndex(1, 2, std::numeric_limits<int>::max());
}

TEST(ValidateArrays, NegativeIndexIsInvalidArgument) {
  expectBadIndex(3, 0, -1);
  expectBadIndex(3, 0, std::numeric_limits<int>::min());
}

TEST(ValidateArrays, NoTrianglesIsInvalidArgument) {
  MeshData m = tetrahedron();
  m.triangles.clear();
  EXPECT_EQ(validateArrays(m).code(), ErrorCode::InvalidArgument);
  EXPECT_EQ(validateArrays(MeshData{}).code(), ErrorCode::InvalidArgument);
}

TEST(ValidateArrays, FiniteInRangeArraysPass) {
  EXPECT_TRUE(validateArrays(tetrahedron()).ok());
  MeshData soup = {{{0, 0, 0}, {1, 0, 0}}, {{0, 0, 1}, {1, 1, 1}}};  // degenerate is fine here
  EXPECT_TRUE(validateArrays(soup).ok());
}

// --- validateClosed: rejected ---------------------------------------------------

TEST(ValidateClosed, MissingTriangleIsOpen) {
  MeshData m = tetrahedron();
  m.triangles.pop_back();  // {1,2,3}: edges (1,2), (2,3), (1,3) lose a side
  expectInvalidGeometry(m, "the surface is open");
  expectInvalidGeometry(m, "edge (1,2)");
}

TEST(ValidateClosed, EdgeSharedByThreeTrianglesIsRejected) {
  MeshData m = tetrahedron();
  m.vertices.emplace_back(1, 1, -1);
  m.triangles.emplace_back(0, 1, 4);
  expectInvalidGeometry(m, "edge (0,1) is shared by 3 triangles");
}

TEST(ValidateClosed, EdgeSharedByFourTrianglesIsRejected) {
  // Two cubes meeting along one edge only.
  expectInvalidGeometry(voxelMesh({Cell(0, 0, 0), Cell(1, 1, 0)}), "is shared by 4 triangles");
}

TEST(ValidateClosed, SameWindingOnAnEdgeIsRejected) {
  MeshData m = tetrahedron();
  std::swap(m.triangles[2][1], m.triangles[2][2]);
  expectInvalidGeometry(m, "inconsistent winding");
}

TEST(ValidateClosed, DuplicatedTriangleIsRejected) {
  MeshData m = tetrahedron();
  m.triangles.push_back(m.triangles[0]);
  expectInvalidGeometry(m, "shared by 3 triangles");
}

TEST(ValidateClosed, RepeatedIndexIsDegenerate) {
  MeshData m = tetrahedron();
  m.triangles[1] = Tri(1, 3, 1);
  expectInvalidGeometry(m, "triangle 1 is degenerate");
}

TEST(ValidateClosed, CollinearVerticesAreDegenerate) {
  MeshData m = tetrahedron();
  m.vertices[3] = Vec3(0.5, 0.5, 0.0);  // on edge (1,2): triangle {1,2,3} has no area
  expectInvalidGeometry(m, "triangle 3 is degenerate");
}

TEST(ValidateClosed, CoincidentVerticesAreDegenerate) {
  MeshData m = tetrahedron();
  m.vertices[3] = m.vertices[1];
  expectInvalidGeometry(m, "is degenerate");
}

TEST(ValidateClosed, TwoDisjointShellsAreRejected) {
  const MeshData m = join(tetrahedron(), translated(tetrahedron(), Vec3(3, 0, 0)));
  expectInvalidGeometry(m, "2 separate shells");
}

TEST(ValidateClosed, NestedShellsAreRejected) {
  // A cavity: a small inside-out cube inside a big cube (manual Fig. 6-10 c).
  MeshData inner = reversed(voxelMesh({Cell(0, 0, 0)}));
  for (Vec3& v : inner.vertices) v = 0.25 * v + Vec3::Constant(0.375);
  expectInvalidGeometry(join(cube(), inner), "separate shells");
}

TEST(ValidateClosed, TetrahedraSharingOneVertexArePinched) {
  // The second tetrahedron is the first mirrored through vertex 0.
  MeshData mirrored = tetrahedron();
  for (Vec3& v : mirrored.vertices) v = -v;
  const MeshData m = join(tetrahedron(), reversed(mirrored), 0);
  ASSERT_EQ(m.vertices.size(), 7u);
  expectInvalidGeometry(m, "vertex 0 is pinched");
}

TEST(ValidateClosed, PinchedVertexOnOneEdgeConnectedShellIsRejected) {
  // Voxels (0,0,0) and (1,1,1) touch only at the point (1,1,1), and a chain of
  // voxels around them joins them by faces: every edge is fine, one shell.
  const std::vector<Cell> cells = {Cell(0, 0, 0),  Cell(0, 0, -1), Cell(1, 0, -1), Cell(2, 0, -1),
                                   Cell(2, 0, 0),  Cell(2, 0, 1),  Cell(2, 1, 1),  Cell(1, 1, 1)};
  const MeshData m = voxelMesh(cells);
  int pinch = -1;
  for (std::size_t i = 0; i < m.vertices.size(); ++i) {
    if (m.vertices[i] == Vec3(1, 1, 1)) pinch = static_cast<int>(i);
  }
  ASSERT_GE(pinch, 0);
  expectInvalidGeometry(m, "vertex " + std::to_string(pinch) + " is pinched");
}

TEST(ValidateClosed, TwoSidedTriangleHasZeroVolume) {
  const MeshData m = {{{0, 0, 0}, {1, 0, 0}, {0, 1, 0}}, {{0, 1, 2}, {0, 2, 1}}};
  expectInvalidGeometry(m, "encloses no volume");
}

TEST(ValidateClosed, FlatTetrahedronHasZeroVolume) {
  MeshData m = tetrahedron();
  m.vertices[3] = Vec3(0.3, 0.3, 0.0);  // coplanar with the others, no triangle degenerate
  expectInvalidGeometry(m, "encloses no volume");
}

// --- validateClosed: accepted ---------------------------------------------------

TEST(ValidateClosed, ManualTetrahedronIsValid) { expectValidUnflipped(tetrahedron()); }

TEST(ValidateClosed, CubeIsValid) {
  const MeshData m = cube();
  ASSERT_EQ(m.vertices.size(), 8u);
  ASSERT_EQ(m.triangles.size(), 12u);
  expectValidUnflipped(m);
  EXPECT_DOUBLE_EQ(signedVolume(m), 1.0);
}

TEST(ValidateClosed, UnusedExtraVertexIsAccepted) {
  MeshData m = cube();
  m.vertices.insert(m.vertices.begin(), Vec3(100, -50, 7));
  for (Tri& t : m.triangles) t += Tri::Ones();
  expectValidUnflipped(m);
}

TEST(ValidateClosed, InsideOutTetrahedronIsFlipped) {
  const MeshData inside_out = reversed(tetrahedron());
  ASSERT_NEAR(signedVolume(inside_out), -1.0 / 6.0, 1e-15);
  MeshData m = inside_out;
  bool flipped = false;
  const Status s = validateClosed(m, flipped);
  ASSERT_TRUE(s.ok()) << s.message();
  EXPECT_TRUE(flipped);
  EXPECT_NEAR(signedVolume(m), 1.0 / 6.0, 1e-15);
  EXPECT_EQ(m.vertices, inside_out.vertices);
}

TEST(ValidateClosed, NonConvexSolidsAreValid) {
  expectValidUnflipped(voxelMesh({Cell(0, 0, 0), Cell(1, 0, 0), Cell(0, 1, 0)}));
  expectValidUnflipped(starPrism());
  // A torus of voxels: genus 1 is one shell with manifold vertices.
  expectValidUnflipped(voxelMesh({Cell(0, 0, 0), Cell(1, 0, 0), Cell(2, 0, 0), Cell(2, 1, 0),
                                  Cell(2, 2, 0), Cell(1, 2, 0), Cell(0, 2, 0), Cell(0, 1, 0)}));
}

TEST(ValidateClosed, ResultDoesNotDependOnScale) {
  // In raw units the areas of these cubes underflow or their squares overflow.
  for (const double scale : {1e-200, 1e-20, 1e20, 1e200}) {
    MeshData m = cube();
    for (Vec3& v : m.vertices) v = scale * v + Vec3::Constant(3.0 * scale);
    SCOPED_TRACE(scale);
    MeshData copy = m;
    bool flipped = true;
    const Status s = validateClosed(copy, flipped);
    EXPECT_TRUE(s.ok()) << s.message();
    EXPECT_FALSE(flipped);
    EXPECT_TRUE(isConvex(m));
    MeshData inside_out = reversed(m);
    flipped = false;
    EXPECT_TRUE(validateClosed(inside_out, flipped).ok());
    EXPECT_TRUE(flipped);
  }
}

TEST(ValidateClosed, ThinButSolidPlateIsValid) {
  MeshData m = cube();
  for (Vec3& v : m.vertices) v.z() *= 1e-8;
  expectValidUnflipped(m);
}

// --- isConvex -------------------------------------------------------------------

TEST(IsConvex, ConvexSolidsAreConvex) {
  EXPECT_TRUE(isConvex(cube()));
  EXPECT_TRUE(isConvex(tetrahedron()));
  EXPECT_TRUE(isConvex(octahedron()));
}

TEST(IsConvex, CubeWithCoplanarSplitFacesIsConvex) {
  const MeshData m = voxelMesh({Cell(0, 0, 0)}, true);
  ASSERT_EQ(m.vertices.size(), 14u);
  ASSERT_EQ(m.triangles.size(), 24u);
  expectValidUnflipped(m);
  EXPECT_TRUE(isConvex(m));
}

TEST(IsConvex, BoxMadeOfVoxelsIsConvex) {
  // Flat edges inside each face of a 2x2x1 box.
  EXPECT_TRUE(isConvex(voxelMesh({Cell(0, 0, 0), Cell(1, 0, 0), Cell(0, 1, 0), Cell(1, 1, 0)})));
}

TEST(IsConvex, RotatedAndMovedConvexSolidsStayConvex) {
  // Rounded coordinates put coplanar faces a few ulps off their common plane; the
  // relative tolerance must absorb that, and must not absorb the L's reflex edge.
  const std::uint64_t seed = 20240611;
  SCOPED_TRACE(seed);
  test::Rng rng(seed);
  const MeshData convex[] = {voxelMesh({Cell(0, 0, 0)}, true),
                             voxelMesh({Cell(0, 0, 0), Cell(1, 0, 0), Cell(0, 1, 0), Cell(1, 1, 0)}),
                             octahedron()};
  const MeshData l_shape = voxelMesh({Cell(0, 0, 0), Cell(1, 0, 0), Cell(0, 1, 0)});
  for (int trial = 0; trial < 50; ++trial) {
    const Mat3 r = test::randomRotation(rng).toRotationMatrix();
    const Vec3 t(test::uniform(rng, -1e3, 1e3), test::uniform(rng, -1e3, 1e3), test::uniform(rng, -1e3, 1e3));
    const double scale = std::pow(10.0, test::uniform(rng, -3, 3));
    auto place = [&](MeshData m) {
      for (Vec3& v : m.vertices) v = scale * (r * v + t);
      return m;
    };
    for (const MeshData& m : convex) EXPECT_TRUE(isConvex(place(m))) << "trial " << trial;
    EXPECT_FALSE(isConvex(place(l_shape))) << "trial " << trial;
  }
}

TEST(IsConvex, UnusedVertexOutsideDoesNotMatter) {
  MeshData m = octahedron();
  m.vertices.emplace_back(10, 10, 10);
  EXPECT_TRUE(isConvex(m));
}

TEST(IsConvex, LShapedPrismIsNotConvex) {
  const MeshData m = voxelMesh({Cell(0, 0, 0), Cell(1, 0, 0), Cell(0, 1, 0)});
  expectValidUnflipped(m);
  EXPECT_FALSE(isConvex(m));
}

TEST(IsConvex, StarPrismIsNotConvex) {
  const MeshData m = starPrism();
  expectValidUnflipped(m);
  EXPECT_FALSE(isConvex(m));
}

TEST(IsConvex, DoublyWoundBipyramidIsNotConvex) {
  // A bipyramid over a pentagram: the equator visits the five points of a regular
  // pentagon in the order 0, 2, 4, 1, 3 and so winds twice around the axis. Every
  // edge is convex, yet the surface is no convex polyhedron: only the check of
  // every vertex against every face plane sees it.
  MeshData m;
  for (int i = 0; i < 5; ++i) {
    const double angle = 2.0 * M_PI * (2 * i % 5) / 5.0;
    m.vertices.emplace_back(std::cos(angle), std::sin(angle), 0.0);
  }
  const int top = 5, bottom = 6;
  m.vertices.emplace_back(0, 0, 1);
  m.vertices.emplace_back(0, 0, -1);
  for (int i = 0; i < 5; ++i) {
    m.triangles.emplace_back(top, i, (i + 1) % 5);
    m.triangles.emplace_back(bottom, (i + 1) % 5, i);
  }
  expectValidUnflipped(m);
  EXPECT_FALSE(isConvex(m));
}

TEST(IsConvex, SlightDentIsNotConvexButSlightBumpIs) {
  // Push one split-face centre inward: its four triangles meet at reflex edges.
  MeshData m = voxelMesh({Cell(0, 0, 0)}, true);
  for (Vec3& v : m.vertices) {
    if (v == Vec3(0.5, 0.5, 1.0)) v.z() -= 1e-6;
  }
  EXPECT_FALSE(isConvex(m));
  // The same centre pulled outward is a flat pyramid on the cube: convex again.
  for (Vec3& v : m.vertices) {
    if (v == Vec3(0.5, 0.5, 1.0 - 1e-6)) v.z() = 1.0 + 1e-6;
  }
  EXPECT_TRUE(isConvex(m));
}

}  // namespace
}  // namespace sc::detail
