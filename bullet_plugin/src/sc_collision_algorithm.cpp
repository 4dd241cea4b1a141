// SPDX-License-Identifier: MIT
// ScCollisionAlgorithm: builds the two group views from the Bullet objects, runs
// the pair tracker, and hands the results to the potential model (impulses), to a
// persistent manifold (Bullet's solver), or to a closest-points query.
#include "sc_collision_algorithm.h"

#include <algorithm>
#include <array>
#include <cmath>
#include <utility>

#include "contact_clusters.h"
#include "contact_response.h"
#include "motion_bound.h"
#include "smartcollision/bullet/plugin.h"
#include "smartcollision/bullet/sc_bullet_shape.h"
#include "step_buffer.h"

namespace sc::bullet {

namespace {

constexpr double kTwoPi = 2.0 * kPi;

btVector3 toBt(const Vec3& v) {
  return btVector3(btScalar(v.x()), btScalar(v.y()), btScalar(v.z()));
}

Vec3 toVec(const btVector3& v) { return Vec3(double(v.x()), double(v.y()), double(v.z())); }

/// Removes from `m` the points an earlier query left, and this one did not give again,
/// that now read deeper than `floor`. A persistent manifold keeps them (a new point
/// takes over only a near cached one): shallower ones are support the query's rows
/// may lack, but read from the points held on the bodies after they moved, some are
/// millimetres deeper than the bodies overlap. A given point keeps its world point on
/// B; `ta`, `tb` are the poses of the manifold's bodies.
void dropStalePoints(btPersistentManifold* m, const detail::ContactCluster& c,
                     const btTransform& ta, const btTransform& tb, double floor) {
  for (int i = m->getNumContacts() - 1; i >= 0; --i) {
    const btManifoldPoint& p = m->getContactPoint(i);
    bool given = false;
    for (int k = 0; k < c.point_count && !given; ++k)
      given = toBt(c.points[static_cast<std::size_t>(k)].on_b) == p.m_positionWorldOnB;
    const double depth =
        double((ta(p.m_localPointA) - tb(p.m_localPointB)).dot(p.m_normalWorldOnB));
    if (!given && depth < floor) m->removeContactPoint(i);
  }
}

/// While alive, the step's statistics count one pair's query alone; at the end the
/// pair's figures are kept in `pair` and added to the step's.
class PairFigures {
 public:
  PairFigures(StepStats& step, StepStats& pair) : step_(step), pair_(pair), saved_(step) {
    step_ = StepStats{};
  }
  ~PairFigures() {
    pair_ = step_;
    accumulate(saved_, step_);
    step_ = saved_;
  }
  PairFigures(const PairFigures&) = delete;
  PairFigures& operator=(const PairFigures&) = delete;

 private:
  StepStats& step_;
  StepStats& pair_;
  StepStats saved_;
};

/// Null when the shape has none (Plugin::shapeModel says why): the pair is ignored.
ModelPtr modelOf(Plugin& plugin, const btCollisionShape* shape) {
  return plugin.shapeModel(shape).value();
}

/// One side of the pair: what the tracker and the response need.
struct Side {
  detail::BodySide body;
  Part part;
  GroupView view;
  btVector3 aabb_min, aabb_max;
  bool dynamic = false;
  double radius = 0.0;  ///< rounded primitives: the model is the core, this the radius
};

/// Radius of a rounded primitive (a sphere is a point, a capsule a segment, plus
/// this radius); 0 for every other shape. Read each step, like Bullet does.
double roundingRadius(const btCollisionShape* shape) {
  switch (shape->getShapeType()) {
    case SPHERE_SHAPE_PROXYTYPE:
      return double(static_cast<const btSphereShape*>(shape)->getRadius());
    case CAPSULE_SHAPE_PROXYTYPE:
      return double(static_cast<const btCapsuleShape*>(shape)->getRadius());
    default:
      return 0.0;
  }
}

void makeSide(const btCollisionObjectWrapper* w, const Model* model, Side& s) {
  const btTransform& t = w->getWorldTransform();
  s.body = detail::bodySide(w);
  s.dynamic = s.body.body != nullptr;
  s.radius = roundingRadius(w->getCollisionShape());
  s.part.model = model;
  s.part.id = 0;
  s.view.parts = &s.part;
  s.view.part_count = 1;
  const btQuaternion q = t.getRotation();
  s.view.placement.world_center = Vec3(t.getOrigin().x(), t.getOrigin().y(), t.getOrigin().z());
  s.view.placement.local_center = Vec3::Zero();
  s.view.placement.orientation = Quat(q.w(), q.x(), q.y(), q.z()).normalized();
  // Tight AABB of the model (the shape's own AABB carries margins).
  const Aabb& b = model->bounds();
  const btVector3 lo(btScalar(b.min.x()), btScalar(b.min.y()), btScalar(b.min.z()));
  const btVector3 hi(btScalar(b.max.x()), btScalar(b.max.y()), btScalar(b.max.z()));
  const btVector3 half = 0.5 * (hi - lo);
  const btVector3 center = t(0.5 * (hi + lo));
  const btMatrix3x3 abs_basis = t.getBasis().absolute();
  const btVector3 extent =
      btVector3(abs_basis[0].dot(half), abs_basis[1].dot(half), abs_basis[2].dot(half)) +
      btVector3(1, 1, 1) * btScalar(s.radius);
  s.aabb_min = center - extent;
  s.aabb_max = center + extent;
}

/// A direction's result for the rounded shapes: the core measured the core point or
/// segment (target radius rt, opponent ro); the surfaces are R = rt + ro closer along
/// the normal. Apart within R becomes a depth R - d along the normal; a depth of the
/// cores grows by R, its contact centre moves out by R.
void inflate(DirectedResult& r, double rt, double ro, double tolerance) {
  const double rr = rt + ro;
  if (r.code != ErrorCode::Ok || rr <= 0.0) return;
  r.point_on_target -= rt * r.normal;
  r.point_on_opponent += ro * r.normal;
  if (r.distance > rr) {
    r.distance -= rr;
    if (r.status == DirectionStatus::Separated && r.distance <= tolerance)
      r.status = DirectionStatus::Touching;
    return;
  }
  const Vec3 current = r.contact_position + r.tpdv;
  r.tpdv = r.distance > 0.0 ? Vec3((r.distance - rr) * r.normal) : Vec3(r.tpdv - rr * r.normal);
  r.distance = -r.tpdv.norm();
  r.contact_position = current - r.tpdv;
  if (r.status != DirectionStatus::Lagging) r.status = DirectionStatus::Penetrating;
}

/// Scalar moment of a side's body (trace / 3 of the world inertia), 0 when static.
double meanMoment(const Side& s) {
  if (s.body.body == nullptr) return 0.0;
  const btVector3 inv = s.body.body->getInvInertiaDiagLocal();
  double sum = 0.0;
  for (int k = 0; k < 3; ++k) sum += inv[k] > 0 ? 1.0 / double(inv[k]) : 0.0;
  return sum / 3.0;
}

double reduced(double a, double b) {
  if (a > 0.0 && b > 0.0) return a * b / (a + b);
  return std::max(a, b);
}

/// A face plane of a piece in world coordinates: outward unit normal, offset.
using detail::WorldPlane;

/// The face planes of a convex piece placed by `world_from_piece` (world), into
/// `planes` (cleared); degenerate triangles give none.
void facePlanes(const Piece& piece, const Rigid& world_from_piece,
                std::vector<WorldPlane>& planes) {
  const MeshData& mesh = piece.mesh();
  planes.clear();
  for (const Tri& t : mesh.triangles) {
    const Vec3& a = mesh.vertices[static_cast<std::size_t>(t[0])];
    const Vec3 n = (mesh.vertices[static_cast<std::size_t>(t[1])] - a)
                       .cross(mesh.vertices[static_cast<std::size_t>(t[2])] - a);
    const double len = n.norm();
    if (!(len > 0.0)) continue;
    const Vec3 normal = world_from_piece.rotation * (n / len);
    planes.push_back({normal, normal.dot(world_from_piece * a)});
  }
}

/// The reference face of a convex piece O (its `planes`) for a convex set of points
/// (T's corners, world): the face plane along whose normal the points penetrate least
/// (the separating-axis test over O's face normals, as box-box clipping chooses it).
/// Stacked boxes of one size read the face below, not a side whose plane a corner
/// also touches; the core's normal of the pair plays no part (an edge-edge normal
/// or a face diagonal reported as an edge would tilt every row).
WorldPlane referenceFace(const std::vector<WorldPlane>& planes, const std::vector<Vec3>& points) {
  WorldPlane best;
  double best_gap = -kInfinity;
  for (const WorldPlane& plane : planes) {
    double gap = kInfinity;
    for (const Vec3& p : points) gap = std::min(gap, plane.distance(p));
    if (gap > best_gap) {
      best_gap = gap;
      best = plane;
    }
  }
  return best;
}

/// Signed distance of `p` from a convex piece (its `planes`): the largest over its
/// face planes (< 0 inside).
double convexSeparation(const std::vector<WorldPlane>& planes, const Vec3& p) {
  double best = -kInfinity;
  for (const WorldPlane& plane : planes) best = std::max(best, plane.distance(p));
  return best;
}

/// The side's model is one convex piece (a box, a hull, a primitive's core).
bool wholeConvex(const Side& s) {
  const auto& pieces = s.part.model->pieces();
  return pieces.size() == 1 && pieces[0]->stats().convex;
}

const Piece* pieceOf(const Side& s, int index) {
  const auto& pieces = s.part.model->pieces();
  if (index < 0 || index >= static_cast<int>(pieces.size())) return nullptr;
  return pieces[static_cast<std::size_t>(index)].get();
}

/// A vertex of a polygon in a plane's frame: (u, v) in the plane, height h above it.
/// No default member values: the clipping's buffers are left unset until written.
struct PlaneVertex {
  double u, v, h;
  bool crossing;  ///< where an edge crosses a clipping line it does not run along
};

/// Polygons of a face: corners of a box's or a small hull's face, and what clipping
/// adds (one per clipping edge). Larger faces are left to the corners' rows.
constexpr int kFaceCorners = 32;
using FacePolygon = std::array<PlaneVertex, 2 * kFaceCorners>;

double cross2(const PlaneVertex& o, const PlaneVertex& a, const PlaneVertex& b) {
  return (a.u - o.u) * (b.v - o.v) - (a.v - o.v) * (b.u - o.u);
}

/// Replaces `p`'s first `n` vertices by their convex hull, counter-clockwise (Andrew's
/// monotone chain); returns its size. `scratch` holds the sorted input.
int convexHull2(FacePolygon& p, int n, FacePolygon& scratch) {
  if (n < 3) return n;
  std::copy(p.begin(), p.begin() + n, scratch.begin());
  std::sort(scratch.begin(), scratch.begin() + n, [](const PlaneVertex& a, const PlaneVertex& b) {
    return a.u < b.u || (a.u == b.u && a.v < b.v);
  });
  int k = 0;
  for (int i = 0; i < n; ++i) {  // lower hull
    while (k >= 2 && cross2(p[k - 2], p[k - 1], scratch[i]) <= 0.0) --k;
    p[k++] = scratch[i];
  }
  for (int i = n - 2, lower = k + 1; i >= 0; --i) {  // upper hull
    while (k >= lower && cross2(p[k - 2], p[k - 1], scratch[i]) <= 0.0) --k;
    p[k++] = scratch[i];
  }
  return k - 1;  // the last repeats the first
}

/// Clips polygon `in` (`n` vertices) to the left of the directed line a -> b
/// (Sutherland-Hodgman), into `out`; heights are interpolated along the edges (exact
/// on a face of T). Returns the size of `out`. An edge whose ends both lie within
/// `reach` of the line runs along it (two faces of one outline, turned a little): its
/// crossing, anywhere along it as the turn goes, is no corner of the contact.
int clipLeft(const FacePolygon& in, int n, const PlaneVertex& a, const PlaneVertex& b, double reach,
             FacePolygon& out) {
  const double length = std::hypot(b.u - a.u, b.v - a.v);
  int m = 0;
  for (int i = 0; i < n && m + 2 <= static_cast<int>(out.size()); ++i) {
    const PlaneVertex& p = in[static_cast<std::size_t>(i)];
    const PlaneVertex& q = in[static_cast<std::size_t>((i + 1) % n)];
    const double sp = cross2(a, b, p), sq = cross2(a, b, q);
    if (sp >= 0.0) out[static_cast<std::size_t>(m++)] = p;
    if ((sp >= 0.0) != (sq >= 0.0)) {
      const double s = sp / (sp - sq);
      const bool along = std::abs(sp) < reach * length && std::abs(sq) < reach * length;
      out[static_cast<std::size_t>(m++)] = {p.u + s * (q.u - p.u), p.v + s * (q.v - p.v),
                                            p.h + s * (q.h - p.h), !along};
    }
  }
  return m;
}

/// True when `x` lies within `reach` of one of the first `n` vertices of `p` (in the plane).
bool nearVertex(const PlaneVertex& x, const FacePolygon& p, int n, double reach) {
  for (int i = 0; i < n; ++i)
    if (std::hypot(x.u - p[static_cast<std::size_t>(i)].u, x.v - p[static_cast<std::size_t>(i)].v) <
        reach)
      return true;
  return false;
}

/// The rows where two convex faces cross with no corner of either there: the corners
/// of their contact polygon that are corners of neither face (edge-edge crossings).
/// T's face is its corners (`corners`, world) within `threshold` of O's reference
/// `face`; O's, the vertices of O's piece `op` (placed by `world_from_o`) on that
/// face's plane. T's face is
/// clipped to O's in the plane, as a box-box manifold does; the corners of either
/// face are rows of their own (convexCorners, and O's direction or
/// addOpponentCorners). A plank lying across another touches it in a square with no
/// such corner, and rested on the core's one point.
void addFaceCrossings(const std::vector<Vec3>& corners, const Piece& op, const Rigid& world_from_o,
                      const WorldPlane& face, double threshold,
                      std::vector<detail::RowPoint>& points) {
  FacePolygon t, o, a, b;  // T's face, O's, and the clipping's two buffers
  const Vec3& n = face.normal;
  const Vec3 e1 = n.unitOrthogonal(), e2 = n.cross(e1);
  const auto inPlane = [&](const Vec3& p) {
    return PlaneVertex{e1.dot(p), e2.dot(p), face.distance(p), false};
  };
  int nt = 0, no = 0;
  for (const Vec3& p : corners) {
    if (!(face.distance(p) < threshold)) continue;
    if (nt == kFaceCorners) return;  // a larger face keeps its corners only
    t[static_cast<std::size_t>(nt++)] = inPlane(p);
  }
  if (nt < 2) return;  // a corner alone is already a row
  // O's face lies on the plane up to the rounding of its vertices' placement.
  for (const Vec3& v : op.mesh().vertices) {
    const Vec3 q = world_from_o * v;
    if (!(std::abs(face.distance(q)) < 1e-3 * threshold)) continue;
    if (no == kFaceCorners) return;
    o[static_cast<std::size_t>(no++)] = inPlane(q);
  }
  nt = convexHull2(t, nt, a);
  no = convexHull2(o, no, a);
  if (nt < 2 || no < 3) return;
  int m = nt;
  std::copy(t.begin(), t.begin() + nt, a.begin());
  FacePolygon* in = &a;
  FacePolygon* out = &b;
  for (int i = 0; i < no && m > 0; ++i) {
    m = clipLeft(*in, m, o[static_cast<std::size_t>(i)], o[static_cast<std::size_t>((i + 1) % no)],
                 threshold, *out);
    std::swap(in, out);
  }
  for (int i = 0; i < m; ++i) {
    const PlaneVertex& x = (*in)[static_cast<std::size_t>(i)];
    if (!x.crossing || !(x.h < threshold) || nearVertex(x, t, nt, threshold) ||
        nearVertex(x, o, no, threshold))
      continue;
    const Vec3 p = x.u * e1 + x.v * e2 + (face.offset + x.h) * n;
    points.push_back({p, n, x.h, true, true});
  }
}

/// The corners of convex piece `tp` of T (at T's current pose moved by `shift`) within
/// `threshold` of convex piece `op` of O, each measured against O's reference face
/// (referenceFace): a corner counts only within the threshold of the piece (a tilted
/// box's corner on a face below leaves the face's other corners out; corners past the
/// face's edges drop).
void convexCorners(const Piece& tp, const Side& t, const Piece& op, const Side& o,
                   const Vec3& shift, double threshold, std::vector<Vec3>& corners,
                   std::vector<WorldPlane>& planes, std::vector<detail::RowPoint>& points) {
  const Rigid world_from_t = t.view.placement.worldFromLocal();
  corners.clear();
  for (const Vec3& v : tp.mesh().vertices) corners.push_back(world_from_t * v + shift);
  const Rigid world_from_o = o.view.placement.worldFromLocal();
  facePlanes(op, world_from_o, planes);
  const WorldPlane face = referenceFace(planes, corners);
  for (const Vec3& p : corners) {
    const double sep = face.distance(p);
    if (sep < threshold && convexSeparation(planes, p) < threshold)
      points.push_back({p, face.normal, sep, true, true});
  }
  addFaceCrossings(corners, op, world_from_o, face, threshold, points);
}

/// O's piece of result `r` when T and O are both one convex polyhedral piece, not
/// rounded (their corners are then measured against each other's faces); else null.
const Piece* convexOpponent(const DirectedResult& r, const Side& t, const Side& o) {
  const Piece* op = pieceOf(o, r.opponent_piece);
  // A piece of a decomposed model has virtual faces: no support plane of the solid.
  const bool convex = op != nullptr && wholeConvex(o) && wholeConvex(t) && o.radius == 0.0 &&
                      t.radius == 0.0 && op->kind() == ModelKind::ClosedPolyhedron;
  return convex ? op : nullptr;
}

/// The support polygon of a convex target piece: its corners (at T's current pose
/// moved by `shift`) within `threshold` of the opponent. Against a convex opponent
/// piece the rows share its reference face (convexCorners). Against a non-convex
/// piece only a face feature's plane (through its contact point, normal n) is the
/// opponent's surface.
void addSupportCorners(const DirectedResult& r, const Side& t, const Side& o, const Vec3& shift,
                       double threshold, std::vector<Vec3>& corners,
                       std::vector<WorldPlane>& planes, std::vector<detail::RowPoint>& points) {
  const Piece* tp = pieceOf(t, r.target_piece);
  if (tp == nullptr || !wholeConvex(t)) return;
  if (const Piece* op = convexOpponent(r, t, o)) {
    convexCorners(*tp, t, *op, o, shift, threshold, corners, planes, points);
    return;
  }
  // A rounded target's core is no polytope.
  if (r.opponent_feature.type != FeatureType::Face) return;
  const Rigid world_from_t = t.view.placement.worldFromLocal();
  const WorldPlane face{r.normal, r.normal.dot(r.point_on_opponent)};
  for (const Vec3& v : tp->mesh().vertices) {
    const Vec3 p = world_from_t * v - t.radius * r.normal + shift;
    if (face.distance(p) < threshold)
      points.push_back({p, face.normal, face.distance(p), false, true});
  }
}

/// The support polygon's other half when O is no target of the pair (static or
/// kinematic: only dynamic bodies are targets), as rows of T: O's corners within
/// `threshold` of T, measured against T's reference face (T moved by `shift`), as
/// O's own direction gives them when O is dynamic. A face of O smaller than T's (a
/// pusher's on a crate) has its corners there and none of T's: without them the rows
/// stood at the one contact point the core reports, a corner of O's face, and a
/// centred push turned T.
void addOpponentCorners(const DirectedResult& r, const Side& t, const Side& o, const Vec3& shift,
                        double threshold, std::vector<Vec3>& corners,
                        std::vector<WorldPlane>& planes, std::vector<detail::RowPoint>& points) {
  const Piece* op = convexOpponent(r, t, o);
  const Piece* tp = pieceOf(t, r.target_piece);
  if (o.dynamic || op == nullptr || tp == nullptr || tp->kind() != ModelKind::ClosedPolyhedron)
    return;
  const std::size_t first = points.size();
  convexCorners(*op, o, *tp, t, -shift, threshold, corners, planes, points);
  // Each is O's corner (moved by -shift) over T's face normal n: T's row is the
  // corner's foot on that face (moved back by shift), along -n.
  for (std::size_t i = first; i < points.size(); ++i) {
    detail::RowPoint& p = points[i];
    p.point += shift - p.separation * p.normal;
    p.normal = -p.normal;
  }
}

/// Smallest-overlap axis of two AABBs as a manifold point (first-seen intersections).
void addOverlapPoint(const Side& a, const Side& b, btManifoldResult* result) {
  int axis = 0;
  double overlap = 0.0;
  for (int k = 0; k < 3; ++k) {
    const double ov =
        std::min(a.aabb_max[k], b.aabb_max[k]) - std::max(a.aabb_min[k], b.aabb_min[k]);
    if (k == 0 || ov < overlap) {
      overlap = ov;
      axis = k;
    }
  }
  if (overlap <= 0.0) return;
  btVector3 n(0, 0, 0);  // from body 1 towards body 0
  n[axis] = (a.aabb_min[axis] + a.aabb_max[axis]) < (b.aabb_min[axis] + b.aabb_max[axis]) ? -1 : 1;
  btVector3 lo = a.aabb_min;
  lo.setMax(b.aabb_min);
  btVector3 hi = a.aabb_max;
  hi.setMin(b.aabb_max);
  btVector3 p = 0.5 * (lo + hi);
  p[axis] = n[axis] > 0 ? hi[axis] : lo[axis];  // on body 1's surface side
  result->addContactPoint(n, p, btScalar(-overlap));
}

/// The core's settings for this pair. Mix weighs translation against rotation by
/// kT / kR; with derived stiffnesses that ratio is m / I of the pair (omega^2 cancels).
SceneSettings pairQuerySettings(const SceneSettings& base, const ContactSettings& contact,
                                const Side sides[2], double dt) {
  SceneSettings query = base;
  const double m = reduced(sides[0].body.inv_mass > 0 ? 1.0 / sides[0].body.inv_mass : 0.0,
                           sides[1].body.inv_mass > 0 ? 1.0 / sides[1].body.inv_mass : 0.0);
  const double inertia = reduced(meanMoment(sides[0]), meanMoment(sides[1]));
  if (!(m > 0.0 && inertia > 0.0)) return query;
  const double omega = kTwoPi / (contact.contact_period_steps * (dt > 0.0 ? dt : 1.0 / 60.0));
  const bool set_t = contact.contact_stiffness > 0.0,
             set_r = contact.contact_torque_stiffness > 0.0;
  query.force_stiffness = set_t ? contact.contact_stiffness : set_r ? m * omega * omega : m;
  query.torque_stiffness = set_r   ? contact.contact_torque_stiffness
                           : set_t ? inertia * omega * omega
                                   : inertia;
  return query;
}

/// Closest-points query (contactTest): one point within the threshold, or the AABB
/// overlap of a pair first seen intersecting.
void reportClosestPoints(const DirectedResult out[2], const Side sides[2], bool swapped,
                         btManifoldResult* result) {
  const double threshold = double(result->m_closestPointDistanceThreshold);
  for (int dir = 0; dir < 2; ++dir) {
    if (out[dir].code == ErrorCode::Ok && out[dir].distance <= threshold) {
      const DirectedResult& r = out[dir];
      const detail::RowPoint p{r.point_on_opponent + r.distance * r.normal, r.normal, r.distance};
      detail::addRows({p}, swapped ? 1 - dir : dir, kInfinity, result);
      return;  // one point per query, as Bullet's convex algorithms report
    }
  }
  if (out[0].code == ErrorCode::InvalidInitialTransformation ||
      out[1].code == ErrorCode::InvalidInitialTransformation)
    addOverlapPoint(sides[swapped ? 1 : 0], sides[swapped ? 0 : 1], result);
}

/// What the direction's response works with, owned by the algorithm.
struct DirectionState {
  Plugin& plugin;
  PairTracker& tracker;
  /// The tracker and results the rows are measured from: `tracker` and its results
  /// in Input, an Input-mode tracker in Mix and Free (their contact configuration is
  /// turned away from the current overlap, so its contacts are not the bodies').
  PairTracker& rows_tracker;
  const DirectedResult* rows_out;
  bool* spring_on;
  bool* in_contact;  ///< per direction: penetrating in the last step
  double* held_depth;  ///< per direction: its depth at the step's detection (0: apart)
  std::vector<detail::RowPoint>& points;
  std::vector<ContactPoint>& contacts;
  std::vector<Vec3>& corners;
  std::vector<WorldPlane>& planes;
  double dt;
};

/// The direction's row points: the result's contact carried to the current pose, the
/// support polygon of a convex target, the core's contacts of a non-convex one.
void gatherPoints(int dir, const Side& t, const Side& o, const Vec3& shift, double threshold,
                  double tolerance, DirectionState& d) {
  const DirectedResult& r = d.rows_out[dir];
  addSupportCorners(r, t, o, shift, threshold, d.corners, d.planes, d.points);
  addOpponentCorners(r, t, o, shift, threshold, d.corners, d.planes, d.points);
  const std::size_t exact = d.points.size();  // corner rows measured on a convex piece
  if (!wholeConvex(t)) {
    // Non-convex: the core's contacts within the threshold at the current pose, each
    // a leaf pair. They are selected at the contact pose, up to the depth away: a
    // second region of the overlap lies farther there than here.
    const double depth = r.penetrating() ? r.tpdv.norm() : 0.0;
    d.rows_tracker.contactPoints(dir, threshold + depth, d.contacts);
    // Rounded sides: the core measured their cores (inflate() for the result).
    const double rr = t.radius + o.radius;
    for (const ContactPoint& c : d.contacts)
      d.points.push_back({c.point_on_target - t.radius * c.normal + shift, c.normal,
                          c.separation - rr + c.normal.dot(shift)});
  }
  // The result's own point (under the opponent's contact point by the depth) when
  // nothing else bears: in Mix and Free its depth is that of the turned contact
  // pose, which the corners measure at the current pose instead.
  if (d.points.empty())
    d.points.push_back({r.point_on_opponent + r.distance * r.normal + shift, r.normal,
                        r.distance + r.normal.dot(shift)});
  // No row measured against a plane deeper than the pair's translational depth plus
  // the tolerance (a core contact's plane may lie beyond the overlap and push too hard).
  const double floor = -(r.penetrating() ? r.tpdv.norm() : 0.0) - tolerance;
  for (std::size_t i = exact; i < d.points.size(); ++i)
    d.points[i].separation = std::max(d.points[i].separation, floor);
  if (detail::anyTouching(d.points, t.body, o.body, d.dt)) ++d.plugin.stepBuffer().stats().touching;
}

/// A direction's response: a recovery push (false), or true when its row points are
/// to be gathered, with the projection of an impact in `shift` (the target's move).
bool respond(const DirectedResult& r, int dir, const Side sides[2], DirectionState& d,
             const detail::PairSpring& spring, const ContactSettings& contact, double tolerance,
             double dt, double threshold, Vec3& shift) {
  const Side& t = sides[dir];
  const Side& o = sides[1 - dir];
  const PluginSettings& ps = d.plugin.settings();
  StepStats& stats = d.plugin.stepBuffer().stats();
  const double period = contact.contact_period_steps * dt;  // recovery time scale
  if (r.code == ErrorCode::InvalidInitialTransformation) {
    ++stats.recovering;
    detail::deliver(d.plugin, t.body, o.body,
                    detail::recoveryImpulse(t.body, o.body, t.aabb_min, t.aabb_max, o.aabb_min,
                                            o.aabb_max, ps.recovery_speed, period),
                    Vec3::Zero());
    return false;
  }
  if (r.code != ErrorCode::Ok) return false;
  // The result the rows are measured from: `r` itself in Input and on convex pairs.
  const DirectedResult& rows = d.rows_out[dir];
  if (r.penetrating() && r.tpdv.dot(r.normal) > 0.0) {
    // A depth whose TPDV points out of the opponent is not one (seen from the core
    // when tracking starts within the tolerance of touching): start over.
    d.tracker.forget(dir);
    return false;
  }
  // The rows take over once the pair was seen apart, or at once when the first depth
  // is small enough that its spring energy fits the recovery bound.
  const double depth = r.tpdv.norm();
  if (!r.penetrating() || depth <= detail::springReach(spring, ps.recovery_speed))
    d.spring_on[dir] = true;
  if (r.penetrating()) {
    ++stats.penetrating;
    // The depth the rows are measured from: on a non-convex pair in Mix and Free the
    // mode's TPDV is only its turned contact pose's share of the way out.
    stats.max_depth = std::max(stats.max_depth, rows.penetrating() ? rows.tpdv.norm() : 0.0);
    stats.max_rotation = std::max(stats.max_rotation, r.rpdv.norm());
    if (!d.spring_on[dir]) {
      ++stats.recovering;
      detail::deliver(
          d.plugin, t.body, o.body,
          detail::recoveryImpulse(t.body, o.body, toBt(r.normal), depth, ps.recovery_speed, period),
          Vec3::Zero());
      return false;
    }
  }
  // Only an impact is projected (detail::projection): a soft row lets a pressed body
  // approach, which is its spring, not an impact. Projections move without turning:
  // they follow the rows' (Input-mode) result, where a Mix or Free result's
  // translation is only its share of the way out.
  const detail::StepBuffer& step = d.plugin.stepBuffer();
  const bool was_in_contact = d.in_contact[dir];
  d.in_contact[dir] = r.penetrating();
  if (!step.impactPass())
    d.held_depth[dir] = rows.code == ErrorCode::Ok && rows.penetrating() ? rows.tpdv.norm() : 0.0;
  if (!(r.distance < threshold)) return false;
  shift = rows.code == ErrorCode::Ok ? detail::projection(rows, t.body, o.body, was_in_contact,
                                                          d.held_depth[dir], step, dt, tolerance)
                                     : Vec3::Zero();
  if (!shift.isZero()) {
    ++stats.projected;
    detail::deliver(d.plugin, t.body, o.body, detail::impactImpulse(shift, t.body, o.body), shift);
  }
  return true;
}

}  // namespace

ScCollisionAlgorithm::ScCollisionAlgorithm(const btCollisionAlgorithmConstructionInfo& ci,
                                           const btCollisionObjectWrapper* body0,
                                           const btCollisionObjectWrapper* body1, Plugin* plugin,
                                           bool closest_points)
    : AlgorithmBase(ci, body0, body1, plugin, closest_points),
      objects_{body0->getCollisionObject(), body1->getCollisionObject()},
      models_{modelOf(*plugin, body0->getCollisionShape()),
              modelOf(*plugin, body1->getCollisionShape())} {
  const btCollisionObjectWrapper* wraps[2] = {body0, body1};
  for (int i = 0; i < 2; ++i) {
    if (!models_[i]) continue;
    const Aabb& b = models_[i]->bounds();  // the farthest corner bounds every vertex
    const double rounding = roundingRadius(wraps[i]->getCollisionShape());
    reach_[i] = b.min.cwiseAbs().cwiseMax(b.max.cwiseAbs()).norm() + rounding;
    const double size = 0.5 * (b.max - b.min).norm() + rounding;
    if (size > 0.0) size_ = std::min(size_, size);
  }
}

double ScCollisionAlgorithm::tolerance() const {
  const PluginSettings& ps = plugin_->settings();
  return std::min(ps.query.tolerance,
                  ps.relative_tolerance > 0.0 ? ps.relative_tolerance * size_ : kInfinity);
}

double ScCollisionAlgorithm::motionSinceQuery(
    const btCollisionObjectWrapper* const wraps[2]) const {
  return detail::motionBound(wraps[0]->getWorldTransform(), queried_[0], reach_[0]) +
         detail::motionBound(wraps[1]->getWorldTransform(), queried_[1], reach_[1]);
}

bool ScCollisionAlgorithm::stillApart(const btCollisionObjectWrapper* const wraps[2],
                                      double threshold) const {
  if (!(queried_gap_ > threshold)) return false;
  // The poses are Bullet's floats: keep a margin of their rounding.
  const double rounding = 1e-6 * (reach_[0] + reach_[1] + queried_gap_);
  return motionSinceQuery(wraps) + rounding < queried_gap_ - threshold;
}

bool ScCollisionAlgorithm::rowsStillHold(const btCollisionObjectWrapper* const wraps[2]) const {
  // A hundredth of the tolerance: far below what the rows resolve, far above the
  // creep of a body at rest (nm per step), so a resting pair is queried again only
  // when something moves it.
  return rows_kept_ && kept_version_ == plugin_->stepBuffer().settingsVersion() &&
         motionSinceQuery(wraps) < 0.01 * tolerance();
}

void ScCollisionAlgorithm::rememberQuery(const btCollisionObjectWrapper* const wraps[2],
                                         const DirectedResult out[2], const Directions& dirs) {
  ever_queried_ = true;
  queried_gap_ = -1.0;
  for (int i = 0; i < 2; ++i) queried_[i] = wraps[i]->getWorldTransform();
  double gap = kInfinity;
  for (int dir = 0; dir < 2; ++dir) {
    if (!(dir == 0 ? dirs.a_target : dirs.b_target)) continue;
    const DirectedResult& r = out[dir];
    if (r.code != ErrorCode::Ok || r.penetrating() || !(r.distance >= 0.0)) return;
    gap = std::min(gap, r.distance);
  }
  if (gap < kInfinity) queried_gap_ = gap;
}

ScCollisionAlgorithm::~ScCollisionAlgorithm() {
  for (btPersistentManifold* m : manifolds_)
    if (m != nullptr) m_dispatcher->releaseManifold(m);
}

void ScCollisionAlgorithm::getAllContactManifolds(btManifoldArray& manifolds) {
  for (btPersistentManifold* m : manifolds_)
    if (m != nullptr) manifolds.push_back(m);
}

namespace {

/// True when patch `c`'s rows are all corners of convex pieces (its support polygon).
bool cornersOnly(const detail::ContactCluster& c) {
  for (int k = 0; k < c.point_count; ++k)
    if (!c.points[static_cast<std::size_t>(k)].exact) return false;
  return c.point_count > 0;
}

/// True when manifold `m` holds rows of patch `c`'s normal.
bool sameNormal(const btPersistentManifold* m, const detail::ContactCluster& c) {
  return m != nullptr && m->getNumContacts() > 0 &&
         toVec(m->getContactPoint(0).m_normalWorldOnB).dot(c.normal) >= detail::kClusterCos;
}

/// Distance from manifold `m`'s points to patch `c`'s nearest row, when `m` holds
/// rows of its normal; else infinity.
double patchDistance(const btPersistentManifold* m, const detail::ContactCluster& c) {
  if (!sameNormal(m, c)) return kInfinity;
  double nearest = kInfinity;
  for (int i = 0; i < m->getNumContacts(); ++i)
    for (int k = 0; k < c.point_count; ++k)
      nearest = std::min(nearest, (toVec(m->getContactPoint(i).getPositionWorldOnB()) -
                                   c.points[static_cast<std::size_t>(k)].on_b)
                                      .norm());
  return nearest;
}

}  // namespace

int ScCollisionAlgorithm::slotFor(const detail::ContactCluster& c, bool taken[kManifolds]) {
  static_assert(kPatches == detail::kMaxClusters);
  // The manifold that held this patch: the nearest of its normal. Two regions of one
  // normal keep a manifold each; a single contact that moves between the ends of a
  // lying capsule keeps both ends' points as support, as Bullet's own manifolds do.
  int best = -1;
  double best_distance = kInfinity;
  for (int i = 0; i < kPatches; ++i) {
    const double d = taken[i] ? kInfinity : patchDistance(manifolds_[i], c);
    if (d < best_distance) {
      best_distance = d;
      best = i;
    }
  }
  for (int i = 0; i < kPatches && best < 0; ++i)  // else an empty one
    if (!taken[i] && (manifolds_[i] == nullptr || manifolds_[i]->getNumContacts() == 0)) best = i;
  for (int i = 0; i < kPatches && best < 0; ++i)  // else any left (its old patch is gone)
    if (!taken[i]) best = i;
  taken[best] = true;
  return best;
}

int ScCollisionAlgorithm::addPatchRows(int slot, const detail::ContactCluster& c, int begin,
                                       int end, double stale_floor, btManifoldResult* result) {
  btPersistentManifold*& m = manifolds_[slot];
  if (m == nullptr) m = m_dispatcher->getNewManifold(objects_[0], objects_[1]);
  if (m->getNumContacts() > 0 && !sameNormal(m, c)) m->clearManifold();
  // A patch of corners is its whole support polygon: the points the motion since
  // they were made has broken go before its rows come in. A full manifold makes room
  // by dropping one of its points, which could be a new row while the broken ones
  // went only after (a box sliding more than the breaking threshold in a step lost
  // one or two of its four ground rows, and rocked). Leaf contacts' patches keep old
  // points as support their rows may lack (dropStalePoints).
  if (cornersOnly(c)) refreshRows(m);
  result->setPersistentManifold(m);
  for (int k = begin; k < end; ++k) {
    const detail::RowCandidate& p = c.points[static_cast<std::size_t>(k)];
    result->addContactPoint(toBt(p.normal), toBt(p.on_b), btScalar(p.separation));
  }
  dropStalePoints(m, c, objects_[0]->getWorldTransform(), objects_[1]->getWorldTransform(),
                  stale_floor);
  result->refreshContactPoints();
  return m->getNumContacts();
}

void ScCollisionAlgorithm::processCollision(const btCollisionObjectWrapper* body0,
                                            const btCollisionObjectWrapper* body1,
                                            const btDispatcherInfo& info,
                                            btManifoldResult* result) {
  // The pair keeps its order for its life; side i is objects_[i] in any case, so
  // the tracker's directions stay attached to the same bodies.
  if (!models_[0] || !models_[1]) return;
  if (plugin_->stepBuffer().rowsPass() && !plugin_->stepBuffer().projected(objects_[0]) &&
      !plugin_->stepBuffer().projected(objects_[1]))
    return;
  const bool swapped = body0->getCollisionObject() != objects_[0];
  const btCollisionObjectWrapper* wraps[2] = {swapped ? body1 : body0, swapped ? body0 : body1};
  Side sides[2];
  for (int i = 0; i < 2; ++i) makeSide(wraps[i], models_[i].get(), sides[i]);

  const PluginSettings& ps = plugin_->settings();
  StepStats& stats = plugin_->stepBuffer().stats();
  const double threshold = double(std::min(
      objects_[0]->getCollisionShape()->getContactBreakingThreshold(gContactBreakingThreshold),
      objects_[1]->getCollisionShape()->getContactBreakingThreshold(gContactBreakingThreshold)));
  const bool impact_pass = plugin_->stepBuffer().impactPass();
  // After the integration only an impact needs a query: a pair in contact that moved
  // less than the threshold is its rows' to hold until the next step's detection.
  if (!closest_points_ && impact_pass && !plugin_->stepBuffer().rowsPass() && ever_queried_ &&
      !(queried_gap_ >= 0.0) && !(motionSinceQuery(wraps) > threshold))
    return;
  // A pair apart by more than its motion since its last query cannot have an impact:
  // the impact pass queries it only when the motion may have closed the gap itself.
  if (!closest_points_ && stillApart(wraps, impact_pass ? 0.0 : threshold)) {
    ++stats.pairs;
    ++stats.skipped;
    return;
  }
  if (!closest_points_ && !impact_pass && rowsStillHold(wraps)) {
    // The manifolds still hold the query's rows: their depths follow the small motion
    // (as Bullet's own algorithms refresh theirs); stale depths would make the rows
    // push a body on after it moved out, a jitter of the size of the bound.
    for (btPersistentManifold* m : manifolds_)
      if (m != nullptr && m->getNumContacts() > 0) refreshRows(m);
    accumulate(stats, queried_stats_);
    ++stats.reused;
    return;
  }
  // This query's figures apart from the step's, to be repeated while its rows hold.
  PairFigures figures(stats, queried_stats_);
  const ContactSettings contact = plugin_->pairSettings(objects_[0], objects_[1]);
  SceneSettings query = pairQuerySettings(ps.query, contact, sides, double(info.m_timeStep));
  query.tolerance = tolerance();
  Directions dirs;
  dirs.a_target = sides[0].dynamic || !sides[1].dynamic || closest_points_;
  dirs.b_target = sides[1].dynamic || closest_points_;
  DirectedResult out[2];
  tracker_.update(sides[0].view, sides[1].view, dirs, query, out);
  for (int dir = 0; dir < 2; ++dir)
    inflate(out[dir], sides[dir].radius, sides[1 - dir].radius, query.tolerance);
  rememberQuery(wraps, out, dirs);

  rows_kept_ = false;
  kept_version_ = plugin_->stepBuffer().settingsVersion();
  if (closest_points_) {
    result->setPersistentManifold(manifold_);
    reportClosestPoints(out, sides, swapped, result);
    return;
  }

  const double dt = double(info.m_timeStep);
  const detail::PairSpring spring = detail::pairSpring(sides[0].body, sides[1].body, contact, dt);
  ++stats.pairs;
  const double row_threshold = detail::rowThreshold(spring, ps, threshold);
  const int projected_before = stats.projected;
  // Rows from an Input-mode tracker when the query turns and a side is non-convex
  // (convex pairs measure their corners at the current pose in any mode).
  const DirectedResult* rows_out = out;
  DirectedResult input_out[2];
  if (query.rotation_mode != RotationMode::Input &&
      !(wholeConvex(sides[0]) && wholeConvex(sides[1]))) {
    SceneSettings input = query;
    input.rotation_mode = RotationMode::Input;
    rows_tracker_.update(sides[0].view, sides[1].view, dirs, input, input_out);
    for (int dir = 0; dir < 2; ++dir)
      inflate(input_out[dir], sides[dir].radius, sides[1 - dir].radius, input.tolerance);
    rows_out = input_out;
  }
  DirectionState state{*plugin_,    tracker_,   rows_out == out ? tracker_ : rows_tracker_,
                       rows_out,    spring_on_, in_contact_,
                       held_depth_, points_,    contacts_,
                       corners_,    planes_,    dt};
  candidates_.clear();
  // Both directions' projections first: each moves its own target, so a direction's
  // rows see its target moved by its shift and its opponent by the other's.
  Vec3 shifts[2] = {Vec3::Zero(), Vec3::Zero()};
  bool gather[2] = {false, false};
  for (int dir = 0; dir < 2; ++dir)
    gather[dir] = respond(out[dir], dir, sides, state, spring, contact, query.tolerance, dt,
                          threshold, shifts[dir]);
  for (int dir = 0; dir < 2; ++dir) {
    points_.clear();
    if (gather[dir])
      gatherPoints(dir, sides[dir], sides[1 - dir], shifts[dir] - shifts[1 - dir], threshold,
                   query.tolerance, state);
    const bool target_is_0 = (swapped ? 1 - dir : dir) == 0;  // in the result's order
    const int convex_body = wholeConvex(sides[1 - dir]) ? (target_is_0 ? 1 : 0) : -1;
    for (const detail::RowPoint& p : points_) {
      if (!(p.separation < row_threshold)) continue;
      // Bullet's frame: the normal from the result's body 1 to its body 0, the point
      // on body 1.
      candidates_.push_back(target_is_0
                                ? detail::RowCandidate{p.point - p.separation * p.normal, p.normal,
                                                       p.separation, p.exact, p.corner, convex_body}
                                : detail::RowCandidate{p.point, -p.normal, p.separation, p.exact,
                                                       p.corner, convex_body});
    }
  }
  // A patch spans half the smaller body: two regions of one overlap (a torus across
  // another touches it twice, often with close normals) keep rows of their own.
  const double patch_radius = 0.5 * std::min(reach_[0], reach_[1]);
  stats.dropped_rows +=
      detail::buildClusters(candidates_, patch_radius, query.tolerance, labels_, clusters_);
  // No kept point deeper than the pair's translational depth plus the tolerance.
  double stale_floor = -query.tolerance;
  for (int dir = 0; dir < 2; ++dir)
    if (out[dir].code == ErrorCode::Ok && out[dir].penetrating())
      stale_floor = std::min(stale_floor, -query.tolerance - out[dir].tpdv.norm());
  bool taken[kManifolds] = {};
  int rows = 0;
  for (const detail::ContactCluster& c : clusters_) {
    const int slot = slotFor(c, taken);
    // A leaf patch's five rows in one manifold of four points: each step one of them
    // found no point of its own, took the place of another (Bullet's widest-area
    // reduction) and both lost their warm starts, and the support changed every step
    // (a heavy cow on a light slab rocked). The rows past four keep a manifold of their
    // own, and only them (old points there are the rows' own past places, no support).
    // A patch of corners (up to 16) is left to the reduction, as before.
    const int held = cornersOnly(c) ? c.point_count : std::min(c.point_count, MANIFOLD_CACHE_SIZE);
    rows += addPatchRows(slot, c, 0, held, stale_floor, result);
    if (held == c.point_count) continue;
    taken[kPatches + slot] = true;
    rows += addPatchRows(kPatches + slot, c, held, c.point_count, kInfinity, result);
  }
  for (int i = 0; i < kManifolds; ++i)
    if (!taken[i] && manifolds_[i] != nullptr) manifolds_[i]->clearManifold();
  stats.rows += rows;
  // Pushes and projections act once: a pair that had one is queried again.
  rows_kept_ = stats.recovering == 0 && stats.projected == 0;
  // An impact's rows stay rigid for the step: they take the approach speed at once
  // (restitution 0), where a soft row would let a fast body on through.
  if (ps.model != ContactModel::Potential || stats.projected != projected_before) return;
  // A set kT bears in one direction: spread over the rows of the patches that share
  // the normal (one region or several).
  for (int i = 0; i < kManifolds; ++i)
    if (taken[i])
      detail::softenRows(manifolds_[i], spring, dt, contact.friction_scale,
                         rowsAlong(manifolds_[i], taken));
}

void ScCollisionAlgorithm::refreshRows(btPersistentManifold* m) const {
  // The points are held in the bodies' frames (btManifoldResult), not in a compound
  // child's: with the child's pose every point of an offset child read as drifted by
  // the offset and was dropped, and the body fell a step whenever its rows were reused.
  m->refreshContactPoints(objects_[0]->getWorldTransform(), objects_[1]->getWorldTransform());
}

int ScCollisionAlgorithm::rowsAlong(const btPersistentManifold* m,
                                    const bool taken[kManifolds]) const {
  if (m->getNumContacts() == 0) return 0;
  const Vec3 normal = toVec(m->getContactPoint(0).m_normalWorldOnB);
  int rows = 0;
  for (int i = 0; i < kManifolds; ++i) {
    const btPersistentManifold* other = manifolds_[i];
    if (taken[i] && other->getNumContacts() > 0 &&
        toVec(other->getContactPoint(0).m_normalWorldOnB).dot(normal) >= detail::kClusterCos)
      rows += other->getNumContacts();
  }
  return rows;
}

}  // namespace sc::bullet
