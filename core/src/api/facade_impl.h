// SPDX-License-Identifier: MIT
// The private state behind SCObject and SCSceneManager, shared by both façade
// files: an object knows the scene it is in, the scene knows its objects.
#pragma once

#include <map>
#include <vector>

#include "sc.h"
#include "smartcollision/scene.h"

struct SCObject::Impl {
  SCenum type = 0;
  bool known_type = false;
  sc::ModelKind kind = sc::ModelKind::ClosedPolyhedron;
  std::vector<sc::PiecePtr> pieces;
  sc::Placement placement;  ///< used while not in a scene
  SCSceneManager* scene = nullptr;
  SCint id = 0;
};

struct SCSceneManager::Impl {
  explicit Impl(sc::ModelKind kind, bool known) : scene(kind), known_type(known) {}
  sc::Scene scene;
  bool known_type;
  std::map<SCint, SCObject*> objects;
};
