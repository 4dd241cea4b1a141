// SPDX-License-Identifier: MIT
// The SmartCollision SDK 2.3 API (user's manual sections 4-8): SCObject and
// SCSceneManager. A thin façade over the modern API in <smartcollision/...>;
// see docs/api.md for the decisions the manual leaves open.
//
// Threads: distinct SCSceneManagers may be driven from distinct threads at once.
// Every call on one SCSceneManager, const ones included, must come from one thread
// at a time (GetStatus reads what UpdateStatus wrote); an SCObject in a scene belongs
// to that scene's thread. AddTriangles on distinct objects may run concurrently
// (not with the same bvhFile). UpdateStatus may use the scene's own worker threads
// (SC_SCENE_MANAGER_THREADS) and returns when they are done. docs/reliability.md,
// "Thread-safety contract", has the details.
//
// Errors: a call that returns an error changes nothing and writes no output.
#pragma once

#include <memory>

#include "smartcollision/export.h"

using SCint = int;
using SCenum = int;
using SCfloat = float;
using SCdouble = double;
using SCbool = bool;

// Results: SC_NO_ERROR is zero, every error is distinct and non-zero.
inline constexpr SCint SC_NO_ERROR = 0;
inline constexpr SCint SC_ERROR_NO_RESULT = 1;
inline constexpr SCint SC_ERROR_UNKNOWN_DISTANCE = SC_ERROR_NO_RESULT;  // manual 8.10
inline constexpr SCint SC_ERROR_INVALID_INITIAL_TRANSFORMATION = 2;
inline constexpr SCint SC_ERROR_INVALID_INTIAL_TRANSFORMATION = SC_ERROR_INVALID_INITIAL_TRANSFORMATION;
inline constexpr SCint SC_ERROR_INVALID_LICENSE = 3;  // defined for old code; never returned
inline constexpr SCint SC_ERROR_INVALID_GEOMETRY = 4;
inline constexpr SCint SC_ERROR_INVALID_ARGUMENT = 5;
inline constexpr SCint SC_ERROR_INVALID_ID = 6;
inline constexpr SCint SC_ERROR_INVALID_OPERATION = 7;
inline constexpr SCint SC_ERROR_FILE = 8;

// Object and scene types.
inline constexpr SCenum SC_OBJECT_TYPE_TRIANGLE_SOUP = 0x0101;
inline constexpr SCenum SC_OBJECT_TYPE_CLOSED_POLYHEDRON = 0x0102;
inline constexpr SCenum SC_OBJECT_TYPE_CLOSED_POLYHEDRA = SC_OBJECT_TYPE_CLOSED_POLYHEDRON;
inline constexpr SCenum SC_SCENE_MANAGER_TRIANGLE_SOUP = 0x0201;
inline constexpr SCenum SC_SCENE_MANAGER_CLOSED_POLYHEDRA = 0x0202;

// The global static group.
inline constexpr SCint SC_GROUP_STATIC = -1;
inline constexpr SCint SC_STATIC_GROUP_ID = SC_GROUP_STATIC;

// Activities of objects, groups and group pairs (manual 8.4).
inline constexpr SCenum SC_ACTIVITY_ACTIVE = 0x0301;
inline constexpr SCenum SC_ACTIVITY_SLEEPING = 0x0302;
inline constexpr SCenum SC_ACTIVITY_PASSIVE = 0x0303;
inline constexpr SCenum SC_ACTIVITY_INACTIVE = 0x0304;
inline constexpr SCenum SC_ACTIVITY_ONE_WAY_ACTIVE = 0x0305;
inline constexpr SCenum SC_ACTIVITY_ONE_WAY_INACTIVE = 0x0306;

// Transformation types (manual Tables 7-1 and 7-2).
inline constexpr SCenum SC_POSITION_ORIGIN = 0x0401;
inline constexpr SCenum SC_POSITION_WORLD_CENTER = 0x0402;
inline constexpr SCenum SC_POSITION_LOCAL_CENTER = 0x0403;
inline constexpr SCenum SC_POSITION_NEW_WORLD_CENTER = 0x0404;
inline constexpr SCenum SC_NEW_WORLD_CENTER = SC_POSITION_NEW_WORLD_CENTER;
inline constexpr SCenum SC_POSITION_NEW_LOCAL_CENTER = 0x0405;
inline constexpr SCenum SC_NEW_LOCAL_CENTER = SC_POSITION_NEW_LOCAL_CENTER;
inline constexpr SCenum SC_ORIENTATION_QUATERNION = 0x0406;
inline constexpr SCenum SC_ORIENTATION_MATRIX = 0x0407;
inline constexpr SCenum SC_TRANSFORMATION_MATRIX = 0x0408;

// Scene manager attributes.
inline constexpr SCenum SC_SCENE_MANAGER_MAX_DISTANCE = 0x0501;        // double
inline constexpr SCenum SC_SCENE_MANAGER_TOLERANCE = 0x0502;           // double
inline constexpr SCenum SC_SCENE_MANAGER_SAFETY_COEFFICIENT = 0x0503;  // double, default 0.49
inline constexpr SCenum SC_SCENE_MANAGER_MAX_ITERATION = 0x0504;       // integer
inline constexpr SCenum SC_SCENE_MANAGER_ROTATION_MODE = 0x0505;       // enum
inline constexpr SCenum SC_SCENE_MANAGER_FORCE_STIFFNESS = 0x0506;     // double
inline constexpr SCenum SC_SCENE_MANAGER_TORQUE_STIFFNESS = 0x0507;    // double
inline constexpr SCenum SC_SCENE_MANAGER_THREADS = 0x0508;             // integer; extension (0 = automatic)
inline constexpr SCenum SC_SCENE_MANAGER_RESOLVE_INITIAL_INTERSECTION = 0x0509;  // integer 0/1; extension
inline constexpr SCenum SC_SCENE_MANAGER_CONTACT_POINTS = 0x050A;  // integer 0/1; extension
inline constexpr SCenum SC_SCENE_MANAGER_TELEPORT_DISTANCE = 0x050B;  // double; extension
inline constexpr SCenum SC_SCENE_MANAGER_PROXY_TRAVEL_RATIO = 0x050C;  // double; extension

// Rotation modes (manual 8.8).
inline constexpr SCenum SC_ROTATION_MODE_NONE = 0x0601;
inline constexpr SCenum SC_ROTATION_MODE_INPUT = 0x0602;  // TPD minimization, the default
inline constexpr SCenum SC_ROTATION_MODE_FREE = 0x0603;   // RPD minimization
inline constexpr SCenum SC_ROTATION_MODE_MIX = 0x0604;    // potential minimization

// Status types for SCSceneManager::GetStatus (manual 8.10).
inline constexpr SCenum SC_STATUS_COUNT = 0x0701;
inline constexpr SCenum SC_PAIR_COUNT = SC_STATUS_COUNT;
inline constexpr SCenum SC_STATUS_RESULT = 0x0702;      // 1 int
inline constexpr SCenum SC_GROUP_ID = 0x0703;           // 2 ints: target, opponent
inline constexpr SCenum SC_OBJECT_ID = 0x0704;          // 2 ints
inline constexpr SCenum SC_PIECE_ID = 0x0705;           // 2 ints
inline constexpr SCenum SC_DISTANCE = 0x0706;           // 1 real
inline constexpr SCenum SC_CONTACT_NORMAL = 0x0707;     // 3 reals
inline constexpr SCenum SC_POINT_ON_TARGET = 0x0708;    // 3 reals
inline constexpr SCenum SC_POINT_ON_OPPONENT = 0x0709;  // 3 reals
inline constexpr SCenum SC_FEATURE_TYPE = 0x070A;       // 2 ints
inline constexpr SCenum SC_FEATURE_ON_TARGET = 0x070B;  // 3 ints
inline constexpr SCenum SC_FEATURE_ON_OPPONENT = 0x070C;  // 3 ints
inline constexpr SCenum SC_TPD_VECTOR = 0x070D;         // 3 reals
inline constexpr SCenum SC_TPD_VECOTR = SC_TPD_VECTOR;
inline constexpr SCenum SC_RPD_VECTOR = 0x070E;         // 3 reals
inline constexpr SCenum SC_RPD_VECOTR = SC_RPD_VECTOR;
inline constexpr SCenum SC_CONTACT_POSITION = 0x070F;   // 3 reals
inline constexpr SCenum SC_CONTACT_ORIENTATION = 0x0710;  // 4 reals {s, vx, vy, vz}
// Extensions (with SC_SCENE_MANAGER_CONTACT_POINTS = 1): every contact of a result.
inline constexpr SCenum SC_CONTACT_POINT_COUNT = 0x0711;  // 1 int
inline constexpr SCenum SC_CONTACT_POINTS = 0x0712;  // 10 reals per contact: point on target,
                                                     // point on opponent, normal, separation
// Extension: what the direction's update found (1 int, one of SC_DIRECTION_*; any
// SC_STATUS_RESULT): touching and penetrating told apart, a lagging proxy flagged.
inline constexpr SCenum SC_DIRECTION_STATUS = 0x0713;

// Direction statuses (sc::DirectionStatus).
inline constexpr SCenum SC_DIRECTION_NOT_COMPUTED = 0x0901;
inline constexpr SCenum SC_DIRECTION_BEYOND_MAX_DISTANCE = 0x0902;
inline constexpr SCenum SC_DIRECTION_FIRST_SEEN_INTERSECTING = 0x0903;
inline constexpr SCenum SC_DIRECTION_SEPARATED = 0x0904;
inline constexpr SCenum SC_DIRECTION_TOUCHING = 0x0905;
inline constexpr SCenum SC_DIRECTION_PENETRATING = 0x0906;
inline constexpr SCenum SC_DIRECTION_LAGGING = 0x0907;

// Feature types.
inline constexpr SCenum SC_FEATURE_VERTEX = 0x0801;
inline constexpr SCenum SC_FEATURE_EDGE = 0x0802;
inline constexpr SCenum SC_FEATURE_FACE = 0x0803;

/// A human-readable message for any result code; never null.
SC_API const char* SCGetErrorString(SCint code);

class SCSceneManager;
namespace sc {
struct Placement;
}

/// Geometry (pieces) and transformation of one object (manual 6, 7).
class SC_API SCObject {
 public:
  explicit SCObject(SCenum type);
  /// Leaves the scene it is in, if any.
  ~SCObject();
  SCObject(const SCObject&) = delete;
  SCObject& operator=(const SCObject&) = delete;

  /// Adds one piece. Validates everything; on error the object is unchanged.
  /// SC_ERROR_FILE: the piece was added, but bvhFile could not be written, or it
  /// passed its checksum yet does not describe this mesh (then it was rebuilt).
  SCint AddTriangles(const SCdouble* vertices, SCint vertexCount, const SCint* triangles,
                     SCint triangleCount, const char* bvhFile = nullptr);
  SCint AddTriangles(const SCfloat* vertices, SCint vertexCount, const SCint* triangles,
                     SCint triangleCount, const char* bvhFile = nullptr);

  /// Table 7-1. SC_ERROR_INVALID_OPERATION once the object is in a scene.
  SCint SetTransformation(SCenum type, const SCdouble* trans);
  SCint SetTransformation(SCenum type, const SCfloat* trans);
  /// Table 7-2; in a scene, the object's current world transformation.
  SCint GetTransformation(SCenum type, SCdouble* trans) const;
  SCint GetTransformation(SCenum type, SCfloat* trans) const;

  struct Impl;

 private:
  friend class SCSceneManager;
  sc::Placement currentPlacement() const;
  std::unique_ptr<Impl> impl_;
};

/// The scene manager (manual 8): objects by id, groups, activities, results.
class SC_API SCSceneManager {
 public:
  /// SC_SCENE_MANAGER_CLOSED_POLYHEDRA or SC_SCENE_MANAGER_TRIANGLE_SOUP. Any other
  /// type (an SC_OBJECT_TYPE_* included): every later call returns
  /// SC_ERROR_INVALID_ARGUMENT, as on an SCObject of unknown type.
  explicit SCSceneManager(SCenum type);
  /// Releases every object still in the scene (the objects themselves live on).
  ~SCSceneManager();
  SCSceneManager(const SCSceneManager&) = delete;
  SCSceneManager& operator=(const SCSceneManager&) = delete;

  /// `object` is not owned and must outlive its membership.
  SCint AddObject(SCint id, SCObject* object);
  SCint DeleteObject(SCint id);
  /// An object already in another group moves to gid, staying where it is (its old
  /// group goes with its last object; both groups' pairs restart). Its own group again:
  /// nothing changes.
  SCint AddObjectToGroup(SCint gid, SCint id);
  SCint DeleteObjectFromGroup(SCint gid, SCint id);
  SCint DeleteFromGroup(SCint gid, SCint id);  ///< spelling of manual List 8-6

  SCint SetTransformation(SCint gid, SCenum type, const SCdouble* trans);
  SCint SetTransformation(SCint gid, SCenum type, const SCfloat* trans);
  SCint GetTransformation(SCint gid, SCenum type, SCdouble* trans) const;
  SCint GetTransformation(SCint gid, SCenum type, SCfloat* trans) const;

  SCint SetActivityObject(SCint id, SCenum activity);
  /// PASSIVE drops the group's tracking state as target; INACTIVE that of every
  /// direction of its pairs. A transformation set between INACTIVE and ACTIVE is a
  /// teleport: the pairs restart from the new pose instead of following a path.
  SCint SetActivityGroup(SCint gid, SCenum activity);
  /// ONE_WAY_*: gid1 is the target.
  SCint SetActivityPair(SCint gid1, SCint gid2, SCenum activity);

  SCint SetAttributeDouble(SCenum attribute, SCdouble value);
  SCint SetAttributeInteger(SCenum attribute, SCint value);
  SCint SetAttributeEnum(SCenum attribute, SCenum value);
  SCint GetAttributeDouble(SCenum attribute, SCdouble* value) const;
  SCint GetAttributeInteger(SCenum attribute, SCint* value) const;
  SCint GetAttributeEnum(SCenum attribute, SCenum* value) const;

  SCint UpdateStatus();
  /// The last UpdateStatus's results, unchanged until the next one (a deleted
  /// object's pair included). SC_STATUS_COUNT: the number of listed pairs.
  SCint GetStatus(SCenum type, SCint* value);
  SCint GetStatus(SCenum type, SCint* value, SCint index, SCbool reverseFlag);
  /// A value beyond float's range gives SC_ERROR_INVALID_ARGUMENT (read it as double).
  SCint GetStatus(SCenum type, SCfloat* value, SCint index, SCbool reverseFlag);
  SCint GetStatus(SCenum type, SCdouble* value, SCint index, SCbool reverseFlag);

  struct Impl;

 private:
  friend class SCObject;
  std::unique_ptr<Impl> impl_;
};
