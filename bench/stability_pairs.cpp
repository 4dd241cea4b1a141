// SPDX-License-Identifier: MIT
// Pair-level rows: each case is a pair of boxes; SmartCollision follows the target
// along an approach from a free pose (its dynamic depth needs a history), the peers
// answer the final pose alone, and everything is compared with the exact depth.
#include "stability_pairs.h"

#include <algorithm>
#include <cstdio>
#include <cstdlib>
#include <memory>
#include <string>

#include "smartcollision/collision.h"
#include "stability_peers.h"

namespace stab {
namespace {

using sc::kPi;
constexpr int kApproachSteps = 40;
constexpr int kSettleUpdates = 10;  // further updates at the final pose: the proxy's steady answer

struct PairCase {
  std::string row;
  Box opponent;                  ///< fixed
  Vec3 target_half;              ///< the moving box
  std::vector<sc::Placement> path;  ///< target poses, last = the measured configuration
  Vec3 local_centre = Vec3::Zero();  ///< target's centre of rotation, box frame
};

Box boxAt(const Vec3& half, const sc::Placement& p) {
  return {half, p.rotation(), p.origin()};
}

sc::Placement placed(const Mat3& r, const Vec3& centre) {
  sc::Placement p;
  p.setOrientation(sc::Quat(r));
  p.setWorldCenter(centre);
  return p;
}

/// Translation along `away` from distance 2 m down to the final pose.
std::vector<sc::Placement> approach(const Mat3& r, const Vec3& centre, const Vec3& away) {
  std::vector<sc::Placement> path;
  for (int i = 0; i <= kApproachSteps; ++i)
    path.push_back(placed(r, centre + away.normalized() * (2.0 * (kApproachSteps - i) / kApproachSteps)));
  return path;
}

std::shared_ptr<sc::Model> boxModel(const Vec3& half) {
  sc::Result<sc::PiecePtr> piece = sc::buildPiece(sc::ModelKind::ClosedPolyhedron, boxMesh(half));
  if (!piece.ok()) {
    std::fprintf(stderr, "box model: %s\n", piece.status().message().c_str());
    std::exit(1);
  }
  return std::make_shared<sc::Model>(sc::ModelKind::ClosedPolyhedron,
                                     std::vector<sc::PiecePtr>{piece.value()});
}

/// The target's result after the path (cold: only the final pose, seeded by EPA).
sc::DirectedResult scRun(const PairCase& c, sc::RotationMode mode, bool cold) {
  const auto target = boxModel(c.target_half), opponent = boxModel(c.opponent.half);
  const sc::Part tp{target.get(), {}, 0}, op{opponent.get(), {}, 1};
  sc::GroupView a{&tp, 1, {}}, b{&op, 1, placed(c.opponent.rotation, c.opponent.centre)};
  sc::SceneSettings settings;
  settings.rotation_mode = mode;
  settings.resolve_initial_intersection = cold;
  sc::PairTracker tracker;
  sc::DirectedResult out[2];
  const std::size_t first = cold ? c.path.size() - 1 : 0;
  const int settle = cold ? 0 : kSettleUpdates;
  for (std::size_t i = first; i < c.path.size() + std::size_t(settle); ++i) {
    a.placement = c.path[std::min(i, c.path.size() - 1)];
    tracker.update(a, b, {true, false}, settings, out);
  }
  return out[0];
}

const char* codeName(sc::ErrorCode code) { return sc::describe(code); }

/// Depth of the target at the reported contact configuration (should be ~0).
double contactDepth(const PairCase& c, const sc::DirectedResult& r) {
  sc::Placement p;
  p.setOrientation(r.contact_orientation);
  p.local_center = c.local_centre;
  p.world_center = r.contact_position;
  return boxDepth(c.opponent, boxAt(c.target_half, p));
}

std::string fmt(const char* format, double x, double y = 0.0) {
  char buf[160];
  std::snprintf(buf, sizeof buf, format, x, y);
  return buf;
}

/// Input and None, translation-only paths: the depth is the exact translational one.
/// Mix and Free may also turn: their contact configuration must touch, and their
/// potential may not exceed that of pure translation (which is always available).
Cell scCell(const PairCase& c, const char* column, sc::RotationMode mode, bool cold, double truth) {
  const sc::DirectedResult r = scRun(c, mode, cold);
  Cell cell{c.row, column, "", std::nan(""), std::nan(""), ""};
  if (r.code != sc::ErrorCode::Ok) {
    cell.outcome = "error";
    cell.note = codeName(r.code);
    return cell;
  }
  const double t = r.tpdv.norm(), angle = r.rpdv.norm();
  const double at_contact = r.penetrating() ? contactDepth(c, r) : 0.0;
  if (mode == sc::RotationMode::Mix || mode == sc::RotationMode::Free) {
    cell.value = t;
    // Free puts translation first: never more than pure translation needs. Mix
    // (kT = kR = 1): never a higher potential than pure translation's.
    const double excess = mode == sc::RotationMode::Free
                              ? std::max(0.0, t - truth)
                              : std::sqrt(std::max(0.0, t * t + angle * angle - truth * truth));
    cell.error = std::max(std::abs(at_contact), excess);
    const Vec3 axis = angle > 0 ? Vec3(r.rpdv / angle) : Vec3::Zero();
    cell.note = fmt("|TPDV| %.4g m, |RPDV| %.4g rad", t, angle) +
                fmt(" about (%.3f, %.3f", axis.x(), axis.y()) + fmt(", %.3f)", axis.z()) +
                fmt(", depth at contact pose %.2g m", at_contact);
  } else {
    cell.value = -r.distance;
    cell.error = std::abs(cell.value - truth);
    cell.note = fmt("reported distance %.6g m, |RPDV| %.3g rad", r.distance, angle);
  }
  if (!std::isfinite(cell.value) || !std::isfinite(cell.error)) cell.outcome = "NaN";
  else cell.outcome = cell.error <= kPassError ? "pass" : "wrong";
  return cell;
}

void naDynamics(std::vector<Cell>& cells, const std::string& row) {
  const char* why = "n/a (pair query, no world to step)";
  for (const char* col : {kScPotential, kScManifold, kBtBox, kBtGImpact})
    cells.push_back({row, col, "n/a", std::nan(""), std::nan(""), why});
}

void peers(std::vector<Cell>& cells, const std::string& row, const Box& a, const Box& b,
           double truth) {
  cells.push_back(peerCell(row, kFclDistance, fclSignedDistance(a, b), truth));
  cells.push_back(peerCell(row, kFclCollide, fclCollide(a, b), truth));
  cells.push_back(peerCell(row, kCcdEpa, ccdEpa(a, b), truth));
  cells.push_back(peerCell(row, kCcdMpr, ccdMpr(a, b), truth));
  cells.push_back(peerCell(row, kBtGjkEpa, bulletGjkEpa(a, b), truth));
}

void translationRow(std::vector<Cell>& cells, PairCase c) {
  const Box b = boxAt(c.target_half, c.path.back());
  Vec3 axis;
  const double truth = std::max(0.0, boxDepth(c.opponent, b, &axis));
  // The dynamic depth is measured from the side the target came from; arriving along
  // the exact depth's axis makes it comparable with the static answer of the peers.
  if (truth > 0) c.path = approach(b.rotation, b.centre, axis);
  cells.push_back({c.row, kTruth, "exact", truth, std::nan(""), "exact box depth [m]"});
  cells.push_back(scCell(c, kScInput, sc::RotationMode::Input, false, truth));
  cells.push_back(scCell(c, kScCold, sc::RotationMode::Input, true, truth));
  cells.push_back(scCell(c, kScMix, sc::RotationMode::Mix, false, truth));
  cells.push_back(scCell(c, kScFree, sc::RotationMode::Free, false, truth));
  cells.push_back(scCell(c, kScNone, sc::RotationMode::None, false, truth));
  peers(cells, c.row, c.opponent, b, truth);
  naDynamics(cells, c.row);
  std::printf("  %-48s exact depth %.6g m\n", c.row.c_str(), truth);
}

Mat3 fromRows(double a, double b, double c, double d, double e, double f, double g, double h,
              double i) {
  Mat3 m;
  m << a, b, c, d, e, f, g, h, i;
  return m;
}

/// FCL #493: two equal cubes with the same tilt, kissing face to face (the reported
/// poses, 17 digits as published); the exact gap is a rounding error.
PairCase fcl493() {
  const Mat3 r = fromRows(0.96193976625564348026, 0.15401279915737359216, 0.22572537250328919556,
                          -0.19134171618254486313, 0.96936494951283913579, 0.15401279915737359216,
                          -0.19509032201612822033, -0.19134171618254486313, 0.96193976625564348026);
  PairCase c{"FCL #493: kissing tilted cubes", {Vec3::Constant(0.25), r, Vec3(2, 0, 1.25)},
             Vec3::Constant(0.25), {}, Vec3::Zero()};
  const Vec3 centre(2.0770063995786869349, 0.48468247475641951239, 1.1543291419087275962);
  c.path = approach(r, centre, centre - c.opponent.centre);
  return c;
}

/// FCL #395: a thin plate and a small tilted box whose EPA polytope gets a
/// zero-area triangle (published sizes are full lengths; halves here).
PairCase fcl395() {
  const Mat3 r = fromRows(0.10758262492983036718, -0.6624881850015212903, -0.74130653817877356637,
                          0.22682184885125472595, -0.709614040775253474, 0.6670830248314786326,
                          -0.96797615037608542021, -0.23991106241273435495, 0.07392465377049164954);
  PairCase c{"FCL #395: degenerate EPA triangle",
             {Vec3(0.23, 0.24, 0.005), Mat3::Identity(), Vec3(-0.721, -0.772, 0.81)},
             Vec3(0.0247605, 0.073, 0.03625), {}, Vec3::Zero()};
  const Vec3 centre(-0.42677133002999478872, -0.76596851247746788882, 0.80746731400091054098);
  c.path = approach(r, centre, Vec3::UnitZ());
  return c;
}

std::vector<PairCase> translationCases() {
  std::vector<PairCase> cases;
  const Vec3 unit = Vec3::Constant(0.5);
  // Touching: face on face, offset sideways so no symmetry helps.
  cases.push_back({"touching contact", {unit, Mat3::Identity(), Vec3::Zero()}, unit,
                   approach(Mat3::Identity(), Vec3(1.0, 0.3, 0.2), Vec3::UnitX())});
  // FCL #301: EPA's distance used an unnormalised direction; it shows when the
  // closest point of the polytope is far from unit length: large boxes, tilted.
  const Mat3 tilt = Eigen::AngleAxisd(0.5, Vec3(1, 2, 3).normalized()).toRotationMatrix();
  cases.push_back({"FCL #301: EPA with large tilted boxes",
                   {Vec3(2, 2, 2), Mat3::Identity(), Vec3::Zero()}, Vec3(1.5, 1.0, 0.5),
                   approach(tilt, Vec3(3.2, 0.4, -0.3), Vec3::UnitX())});
  cases.push_back(fcl395());
  cases.push_back(fcl493());
  // libccd #25: cubes of side 2 stacked with 0.1 overlap, axis-aligned.
  cases.push_back({"libccd #25: stacked cubes, 0.1 overlap",
                   {Vec3::Ones(), Mat3::Identity(), Vec3::Zero()}, Vec3::Ones(),
                   approach(Mat3::Identity(), Vec3(0, 0, 1.9), Vec3::UnitZ())});
  // libccd #49: MPR divides by a zero depth: exactly touching, fully symmetric.
  cases.push_back({"libccd #49: MPR at zero depth", {unit, Mat3::Identity(), Vec3::Zero()}, unit,
                   approach(Mat3::Identity(), Vec3(0, 0, 1), Vec3::UnitZ())});
  // Deep: a cube sunk 80% of its size into a slab from above.
  cases.push_back({"deep penetration", {Vec3(2, 0.5, 2), Mat3::Identity(), Vec3::Zero()}, unit,
                   approach(Mat3::Identity(), Vec3(0.3, 0.2, 0.1), Vec3::UnitY())});
  for (PairCase& c : cases) c.local_centre = Vec3::Zero();
  return cases;
}

// ---------------------------------------------------------------- rotational penetration

/// Manual Fig. 5-11: a bar turning about one bottom edge held 1 cm above a slab;
/// turned 5 degrees past flat, its far end is 16 cm deep. A translation must lift
/// the whole bar; turning back by under 5 degrees frees it.
struct Lever {
  Box ground{Vec3(3, 0.5, 3), Mat3::Identity(), Vec3(0, -0.5, 0)};
  Vec3 half{1.0, 0.05, 0.05};
  Vec3 pivot_local{-1.0, -0.05, 0.0};
  Vec3 pivot_world{-1.0, 0.01, 0.0};
  double final_angle = -5.0 * kPi / 180.0;

  sc::Placement at(double angle) const {
    sc::Placement p;
    p.setOrientation(sc::Quat(rotationZ(angle)));
    p.local_center = pivot_local;
    p.world_center = pivot_world;
    return p;
  }
  double depth(double angle) const { return std::max(0.0, boxDepth(ground, boxAt(half, at(angle)))); }
};

struct Truth {
  double t, r;  ///< translation [m] and rotation [rad] back to contact
};

/// Smallest turn back that frees the bar (bisection on the exact depth).
double freeAngle(const Lever& l) {
  double lo = l.final_angle, hi = 0.0;
  for (int i = 0; i < 100; ++i) {
    const double mid = 0.5 * (lo + hi);
    (l.depth(mid) > 0 ? lo : hi) = mid;
  }
  return hi;
}

/// Each mode's exact answer. Input: translation only. None: orientation at the impact
/// on the path (the lever turns about a fixed pivot: the touching angle, no
/// translation, as Free). Free: no translation, least turn. Mix (kT = kR = 1):
/// least t^2 + r^2 over the turn back (fine scan; the best translation at each angle
/// is that angle's translational depth).
Truth truthFor(const Lever& l, sc::RotationMode mode) {
  const double now = l.final_angle;
  switch (mode) {
    case sc::RotationMode::Input:
      return {l.depth(now), 0.0};
    case sc::RotationMode::None:
    case sc::RotationMode::Free:
      return {0.0, freeAngle(l) - now};
    case sc::RotationMode::Mix:
      break;
  }
  Truth best{l.depth(now), 0.0};
  const int n = 20000;
  for (int i = 1; i <= n; ++i) {
    const double a = now + (freeAngle(l) - now) * i / n;
    const double t = l.depth(a), r = a - now;
    if (t * t + r * r < best.t * best.t + best.r * best.r) best = {t, r};
  }
  return best;
}

void rotationRow(std::vector<Cell>& cells) {
  const std::size_t first = cells.size();  // the truth cell goes first, as in other rows
  const Lever l;
  const std::string row = "rotational penetration (Fig. 5-11)";
  PairCase c{row, l.ground, l.half, {}, l.pivot_local};
  for (double deg = 10.0; deg >= -5.0 - 1e-9; deg -= 0.25)
    c.path.push_back(l.at(deg * kPi / 180.0));
  const std::pair<const char*, sc::RotationMode> modes[] = {
      {kScInput, sc::RotationMode::Input}, {kScMix, sc::RotationMode::Mix},
      {kScFree, sc::RotationMode::Free}, {kScNone, sc::RotationMode::None}};
  for (const auto& [column, mode] : modes) {
    const Truth truth = truthFor(l, mode);
    const sc::DirectedResult r = scRun(c, mode, false);
    Cell cell{row, column, "", std::nan(""), std::nan(""), ""};
    if (r.code != sc::ErrorCode::Ok) {
      cells.push_back({row, column, "error", std::nan(""), std::nan(""), codeName(r.code)});
      continue;
    }
    const double t = r.tpdv.norm(), angle = r.rpdv.norm();
    cell.value = t;
    // The bar is 2 m long: a turn of r moves its far end 2 r.
    cell.error = std::max(std::abs(t - truth.t), 2.0 * std::abs(angle - std::abs(truth.r)));
    cell.note = fmt("|TPDV| %.4g m, |RPDV| %.4g rad; ", t, angle) +
                fmt("exact %.4g m, %.4g rad", truth.t, std::abs(truth.r));
    cell.outcome = !std::isfinite(cell.error) ? "NaN" : cell.error <= kPassError ? "pass" : "wrong";
    cells.push_back(cell);
  }
  PairCase cold = c;
  const double truth = l.depth(l.final_angle);
  cells.insert(cells.begin() + std::ptrdiff_t(first), {row, kTruth, "exact", truth, std::nan(""),
                                                      "exact translational depth [m]"});
  cells.push_back(scCell(cold, kScCold, sc::RotationMode::Input, true, truth));
  peers(cells, row, l.ground, boxAt(l.half, c.path.back()), truth);
  naDynamics(cells, row);
  std::printf("  %-48s exact translational depth %.6g m\n", row.c_str(), truth);
}

}  // namespace

std::vector<Cell> runPairRows() {
  std::vector<Cell> cells;
  for (const PairCase& c : translationCases()) translationRow(cells, c);
  rotationRow(cells);
  return cells;
}

}  // namespace stab
