// SPDX-License-Identifier: MIT
// The knots pile of the stacking demo and of bench/pile_rotation_modes: one layout, so
// that the bench measures the scene the demo shows.
#pragma once

#include <btBulletDynamicsCommon.h>

#include <vector>

namespace sc::demo {

/// A static wall of the pile's box (a btBoxShape).
struct PileWall {
  btVector3 half_extents;
  btVector3 center;
};

/// A 3 m x 3 m box of walls 1.2 m high (its floor first).
inline std::vector<PileWall> pileWalls() {
  return {{{1.5f, 0.05f, 1.5f}, {0, 0.05f, 0}},
          {{0.05f, 0.6f, 1.5f}, {-1.55f, 0.6f, 0}},
          {{0.05f, 0.6f, 1.5f}, {1.55f, 0.6f, 0}},
          {{1.5f, 0.6f, 0.05f}, {0, 0.6f, -1.55f}},
          {{1.5f, 0.6f, 0.05f}, {0, 0.6f, 1.55f}}};
}

/// Where a body of the pile starts. The turn stays a quaternion: through a
/// btTransform's float matrix and back it would round differently.
struct PileBodyPose {
  btVector3 position;
  btQuaternion rotation;
};

/// Poses of `count` bodies (0.5 m) dropped into the box in layers of four, turned at
/// random by `seed` (the same turns on every machine: a plain LCG).
inline std::vector<PileBodyPose> pileBodyPoses(int count, unsigned seed) {
  auto next = [&seed] { return (seed = seed * 1103515245u + 12345u) / 4294967296.0; };
  std::vector<PileBodyPose> poses;
  for (int i = 0; i < count; ++i) {
    const btVector3 p(btScalar(-0.9 + 0.6 * (i % 4)), btScalar(0.5 + 0.6 * (i / 4)),
                      btScalar(-0.3 + 0.6 * ((i / 2) % 2)));
    // Drawn in sequence: angle, then z, then x (the order GCC gave the former nested
    // call, whose argument order C++ leaves unspecified: the drops' figures stand).
    const double angle = 6.283 * next(), z = next() - 0.5, x = next() - 0.5;
    const btVector3 axis(btScalar(x), 1, btScalar(z));
    poses.push_back({p, btQuaternion(axis.normalized(), btScalar(angle))});
  }
  return poses;
}

}  // namespace sc::demo
