// SPDX-License-Identifier: MIT
#include "penetration/contact_rows.h"

#include <algorithm>

#include "geometry/math_util.h"
#include "query/epa.h"

namespace sc::detail {

Vec3 exitNormal(GroupPairQuery& query, const LeafContact& c, const Rigid& previous_proxy) {
  const LeafContact before = query.pairAt(c.t_leaf, c.o_leaf, previous_proxy);
  if (!before.intersecting) return before.normal;
  // The previous proxy intersects or touches too (a goal reached exactly touching):
  // the leaves' own exit direction, where the direction between their centres would
  // be any direction at all (a face-on-face contact offset sideways turned FREE's
  // proxy a little more at every update).
  const Leaf t = query.targetLeaf(c.t_leaf);
  const Leaf o = query.opponentLeaf(c.o_leaf);
  const EpaResult e =
      penetrationDepth(*t.poly, previous_proxy * t.group_from_leaf, *o.poly, o.group_from_leaf);
  if (e.normal.allFinite() && e.normal.norm() > 0.5) return e.normal.normalized();
  const Vec3 t_center = previous_proxy * t.center;
  return normalizedOr(t_center - o.center, Vec3::UnitZ());
}

void buildContactRows(GroupPairQuery& query, const Rigid& pose, const Vec3& center_at_pose,
                      const std::vector<LeafContact>& contacts, const Rigid& previous_proxy,
                      std::vector<ContactRow>& rows, double near) {
  rows.clear();
  for (int i = 0; i < static_cast<int>(contacts.size()); ++i) {
    const LeafContact& c = contacts[i];
    ContactRow row;
    row.normal = c.intersecting ? exitNormal(query, c, previous_proxy) : c.normal;
    row.gap = query.separationAlong(c.t_leaf, c.o_leaf, pose, row.normal);
    row.contact = i;
    // One row per target vertex near the separating plane: a face or edge in contact
    // must not turn into the opponent about any of its corners, which a single
    // witness point would allow.
    const Leaf& leaf = query.targetLeaves()[c.t_leaf];
    const Rigid o_from_leaf = pose * leaf.group_from_leaf;
    double lowest = kInfinity;
    for (const Vec3& v : leaf.poly->vertices)
      lowest = std::min(lowest, row.normal.dot(o_from_leaf * v));
    for (const Vec3& v : leaf.poly->vertices) {
      const Vec3 p = o_from_leaf * v;
      const double above = row.normal.dot(p) - lowest;
      if (above > near) continue;
      ContactRow corner = row;
      corner.gap = row.gap + above;
      corner.lever = p - center_at_pose;
      rows.push_back(corner);
    }
  }
}

void buildContactPatches(GroupPairQuery& query, const Rigid& pose,
                         const std::vector<LeafContact>& contacts, const Rigid& previous_proxy,
                         std::vector<ContactPatch>& patches) {
  patches.resize(contacts.size());
  for (std::size_t i = 0; i < contacts.size(); ++i) {
    const LeafContact& c = contacts[i];
    ContactPatch& p = patches[i];
    p.normal = c.intersecting ? exitNormal(query, c, previous_proxy) : c.normal;
    p.gap = query.separationAlong(c.t_leaf, c.o_leaf, pose, p.normal);
    const Leaf& leaf = query.targetLeaves()[c.t_leaf];
    p.o_from_leaf = pose * leaf.group_from_leaf;
    p.leaf_normal = p.o_from_leaf.rotation.transpose() * p.normal;
    p.poly = leaf.poly;
    p.hint = std::min(p.hint, static_cast<int>(p.poly->vertices.size()) - 1);
    p.lowest = p.leaf_normal.dot(p.poly->vertices[p.poly->support(-p.leaf_normal, p.hint)]);
    p.center = pose * leaf.center;
    p.radius = leaf.radius;
    p.contact = static_cast<int>(i);
  }
}

namespace {

using Vec6 = Eigen::Matrix<double, 6, 1>;

/// A row of the working set that the set's own solution still misses by less than
/// this (of the rows' magnitudes, as kRowTolerance) is missed by rounding, not a
/// wedge: FREE's rotation weight (1e-6 rho^2) spreads the LDP's columns by ~1e3 / rho,
/// and its point then misses a set row by ~1e-9 of the magnitudes. A wedge (nearly
/// opposite rows) misses by a good part of them.
constexpr double kSetRowTolerance = 1e-6;

/// The vertices of patches[i] within `near` of its plane, listed on first need.
std::pair<const int*, const int*> nearVertices(const ContactPatch& p, std::size_t i, double near,
                                               PatchQpWork& w) {
  if (w.near_range[i].first < 0) {
    w.near_range[i].first = static_cast<int>(w.near_list.size());
    const PolytopeArray<Vec3>& vs = p.poly->vertices;
    for (int v = 0; v < static_cast<int>(vs.size()); ++v)
      if (p.leaf_normal.dot(vs[static_cast<std::size_t>(v)]) - p.lowest <= near)
        w.near_list.push_back(v);
    w.near_range[i].second = static_cast<int>(w.near_list.size());
  }
  const int* base = w.near_list.data();
  return {base + w.near_range[i].first, base + w.near_range[i].second};
}

/// The most violated row of patches[i] at twist z: its slack, and the vertex in `vertex`.
double mostViolated(const std::vector<ContactPatch>& patches, std::size_t i, const Vec3& y,
                    const Vec6& z, double skin, double near, PatchQpWork& w, int& vertex) {
  const ContactPatch& p = patches[i];
  const Vec3 turn = p.normal.cross(z.tail<3>());
  // slack_v = offset + v . d: the least over the vertices within `near` of the plane.
  const Vec3 d = p.leaf_normal + p.o_from_leaf.rotation.transpose() * turn;
  const double offset = p.normal.dot(z.head<3>()) + (p.o_from_leaf.translation - y).dot(turn) -
                        skin + p.gap - p.lowest;
  const PolytopeArray<Vec3>& vs = p.poly->vertices;
  vertex = p.poly->support(-d, p.hint);
  if (p.leaf_normal.dot(vs[static_cast<std::size_t>(vertex)]) - p.lowest > near) {
    // The least over all vertices is not a row: the least over the rows, by a scan.
    const auto [begin, end] = nearVertices(p, i, near, w);
    double least = kInfinity;
    for (const int* v = begin; v != end; ++v) {
      const double value = vs[static_cast<std::size_t>(*v)].dot(d);
      if (value < least) {
        least = value;
        vertex = *v;
      }
    }
  }
  return offset + vs[static_cast<std::size_t>(vertex)].dot(d);
}

/// A bound on rowScale's terms |b_i| + sum_j |a_ij z_j| over the rows of `p`.
double rowTermsBound(const ContactPatch& p, const Vec3& y, const Vec6& z, double skin,
                     double near) {
  const double lever = (p.center - y).norm() + p.radius;
  return std::max(std::abs(skin - p.gap), std::abs(skin - p.gap - near)) +
         p.normal.cwiseProduct(z.head<3>()).cwiseAbs().sum() + lever * z.tail<3>().lpNorm<1>();
}

ContactRow rowOf(const ContactPatch& p, int vertex, const Vec3& y) {
  ContactRow row;
  const Vec3& v = p.poly->vertices[vertex];
  row.normal = p.normal;
  row.gap = p.gap + p.leaf_normal.dot(v) - p.lowest;
  row.lever = p.o_from_leaf * v - y;
  row.contact = p.contact;
  return row;
}

/// Appends a row to the working set's arrays.
void addRow(const ContactRow& row, double skin, PatchQpWork& w) {
  const auto at = static_cast<Eigen::Index>(w.rows.size());
  w.rows.push_back(row);
  if (w.qp.sub_a.cols() != 6) w.qp.sub_a.resize(0, 6);
  if (w.qp.sub_a.rows() <= at) {  // grows geometrically: rarely
    w.qp.sub_a.conservativeResize(std::max<Eigen::Index>(2 * (at + 1), 64), 6);
    w.qp.sub_b.conservativeResize(w.qp.sub_a.rows());
  }
  w.qp.sub_a.row(at) << row.normal.transpose(), row.lever.cross(row.normal).transpose();
  w.qp.sub_b[at] = skin - row.gap;
}

}  // namespace

void solvePatchQp(const std::vector<ContactPatch>& patches, const Vec3& y, const Vec6& goal,
                  const Vec6& weights, double skin, double near, PatchQpWork& w) {
  w.rows.clear();
  w.ids.clear();
  w.qp.feasible = true;
  w.qp.z = goal;
  w.qp.lambda.clear();
  w.near_list.clear();
  w.near_range.assign(patches.size(), {-1, -1});
  double length = 0.0;  // the largest violation at the goal, over every row
  int vertex = 0;
  for (std::size_t i = 0; i < patches.size(); ++i)
    length = std::max(length, -mostViolated(patches, i, y, goal, skin, near, w, vertex));
  if (length <= 0.0) return;  // the goal itself is feasible
  // The optimum over rows that keep every other row is the optimum over all; a round
  // adds a row not in the set, so it ends. A row of the set still violated beyond
  // rounding is a wedge (nearly opposite rows): no point, as the all-rows solve
  // judges it.
  for (;;) {
    const Vec6 z = w.qp.z;
    double scale = length;
    for (const ContactPatch& p : patches)
      scale = std::max(scale, length + rowTermsBound(p, y, z, skin, near));
    const std::size_t before = w.rows.size();
    for (std::size_t i = 0; i < patches.size(); ++i) {
      const double slack = mostViolated(patches, i, y, z, skin, near, w, vertex);
      if (slack >= -kRowTolerance * scale) continue;
      const std::pair<int, int> id(static_cast<int>(i), vertex);
      if (std::find(w.ids.begin(), w.ids.end(), id) != w.ids.end()) {
        if (slack >= -kSetRowTolerance * scale) continue;  // the set's own rounding
        w.qp.feasible = false;
        break;
      }
      w.ids.push_back(id);
      addRow(rowOf(patches[i], vertex, y), skin, w);
    }
    if (!w.qp.feasible || w.rows.size() == before) break;
    const auto count = static_cast<Eigen::Index>(w.rows.size());
    // The rows only grow within this call (same goal, weights, length): the last
    // round's solution starts this one.
    const auto kept = before > 0 ? static_cast<Eigen::Index>(before) : 0;
    if (!solveLdpStep(goal, weights, w.qp.sub_a.topRows(count), w.qp.sub_b.head(count), length,
                      w.qp, kept)) {
      w.qp.feasible = false;
      break;
    }
  }
  if (!w.qp.feasible) {
    w.qp.z = goal;
    w.qp.lambda.assign(w.rows.size(), 0.0);
  }
}

}  // namespace sc::detail
