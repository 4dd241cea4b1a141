// SPDX-License-Identifier: MIT
// FCL, libccd and Bullet GJK-EPA on two boxes, isolated in a forked child each.
#include "stability_peers.h"

#include <signal.h>
#include <sys/wait.h>
#include <unistd.h>

#include <cstdio>
#include <cstring>
#include <exception>
#include <functional>
#include <utility>

#if SC_BENCH_HAVE_FCL
#include <fcl/fcl.h>
#endif
#if SC_BENCH_HAVE_CCD
#include "ccd_problem.h"
#endif
#include <BulletCollision/CollisionShapes/btConvexHullShape.h>
#include <BulletCollision/NarrowPhaseCollision/btGjkEpa2.h>

namespace stab {
namespace {

constexpr unsigned kChildSeconds = 5;  // a peer still looping after this has hung

/// What crosses the pipe from the child: plain data only.
struct Wire {
  int status;
  double depth;
  char message[200];
};

/// Runs `query` in a child; its result, or how the child ended.
PeerOut isolated(const std::function<PeerOut()>& query) {
  int fds[2];
  if (pipe(fds) != 0) return {PeerStatus::Crash, 0.0, "pipe failed"};
  std::fflush(nullptr);
  const pid_t pid = fork();
  if (pid == 0) {
    close(fds[0]);
    alarm(kChildSeconds);
    PeerOut out;
    try {
      out = query();
    } catch (const std::exception& e) {
      out = {PeerStatus::Exception, 0.0, e.what()};
    }
    Wire w{int(out.status), out.depth, {}};
    std::snprintf(w.message, sizeof w.message, "%s", out.message.c_str());
    if (write(fds[1], &w, sizeof w) != ssize_t(sizeof w)) _exit(2);
    _exit(0);
  }
  close(fds[1]);
  Wire w{};
  const bool got = read(fds[0], &w, sizeof w) == ssize_t(sizeof w);
  close(fds[0]);
  int wstatus = 0;
  waitpid(pid, &wstatus, 0);
  if (got) return {PeerStatus(w.status), w.depth, w.message};
  if (WIFSIGNALED(wstatus) && WTERMSIG(wstatus) == SIGALRM)
    return {PeerStatus::Hang, 0.0, "no answer within 5 s"};
  const int sig = WIFSIGNALED(wstatus) ? WTERMSIG(wstatus) : 0;
  return {PeerStatus::Crash, 0.0, std::string("signal ") + std::to_string(sig) + " (" +
                                      (sig ? strsignal(sig) : "exit") + ")"};
}

std::string oneLine(std::string s) {
  const std::size_t nl = s.find('\n');
  if (nl != std::string::npos) s = s.substr(0, nl);
  return s.size() > 120 ? s.substr(0, 120) + "..." : s;
}

#if SC_BENCH_HAVE_FCL
fcl::Transform3d fclPose(const Box& b) {
  fcl::Transform3d t = fcl::Transform3d::Identity();
  t.linear() = b.rotation;
  t.translation() = b.centre;
  return t;
}
#endif

#if SC_BENCH_HAVE_CCD
void ccdSupport(const void* obj, const ccd_vec3_t* dir, ccd_vec3_t* out) {
  const Vec3 s = static_cast<const Box*>(obj)->support(Vec3(dir->v[0], dir->v[1], dir->v[2]));
  ccdVec3Set(out, s.x(), s.y(), s.z());
}

void ccdCentre(const void* obj, ccd_vec3_t* out) {
  const Vec3& c = static_cast<const Box*>(obj)->centre;
  ccdVec3Set(out, c.x(), c.y(), c.z());
}

/// libccd with its defaults (first direction, tolerances) as a user would call it.
PeerOut ccdQuery(const Box& a, const Box& b, bool mpr) {
  return isolated([&] {
    ccd_t ccd = sc_bench::ccdProblem(ccdSupport, ccdCentre);
    ccd_real_t depth = 0;
    ccd_vec3_t dir, pos;
    const int r = mpr ? ccdMPRPenetration(&a, &b, &ccd, &depth, &dir, &pos)
                      : ccdGJKPenetration(&a, &b, &ccd, &depth, &dir, &pos);
    const bool finite_dir = std::isfinite(dir.v[0]) && std::isfinite(dir.v[1]) && std::isfinite(dir.v[2]);
    PeerOut o{r == 0 ? PeerStatus::Penetrating : PeerStatus::Apart, r == 0 ? double(depth) : 0.0,
              r == 0 ? (finite_dir ? "" : "direction NaN") : "reports no intersection"};
    if (r == 0 && !finite_dir) o.depth = std::nan("");
    return o;
  });
}
#endif

}  // namespace

// Without a peer library at build time its queries report Missing.
#if SC_BENCH_HAVE_FCL
PeerOut fclSignedDistance(const Box& a, const Box& b) {
  return isolated([&] {
    const fcl::Boxd ga(2 * a.half), gb(2 * b.half);
    fcl::DistanceRequestd request;
    request.enable_signed_distance = true;  // the EPA path of the issues
    request.enable_nearest_points = true;
    request.gjk_solver_type = fcl::GST_LIBCCD;
    fcl::DistanceResultd result;
    fcl::distance(&ga, fclPose(a), &gb, fclPose(b), request, result);
    const double d = result.min_distance;
    return d < 0 ? PeerOut{PeerStatus::Penetrating, -d, ""} : PeerOut{PeerStatus::Apart, -d, ""};
  });
}

PeerOut fclCollide(const Box& a, const Box& b) {
  return isolated([&] {
    const fcl::Boxd ga(2 * a.half), gb(2 * b.half);
    fcl::CollisionRequestd request(1, true);
    request.gjk_solver_type = fcl::GST_LIBCCD;
    fcl::CollisionResultd result;
    fcl::collide(&ga, fclPose(a), &gb, fclPose(b), request, result);
    if (!result.isCollision()) return PeerOut{PeerStatus::Apart, 0.0, "reports no collision"};
    return PeerOut{PeerStatus::Penetrating, result.getContact(0).penetration_depth, ""};
  });
}
#else
PeerOut fclSignedDistance(const Box&, const Box&) { return {}; }
PeerOut fclCollide(const Box&, const Box&) { return {}; }
#endif

#if SC_BENCH_HAVE_CCD
PeerOut ccdEpa(const Box& a, const Box& b) { return ccdQuery(a, b, false); }
PeerOut ccdMpr(const Box& a, const Box& b) { return ccdQuery(a, b, true); }
#else
PeerOut ccdEpa(const Box&, const Box&) { return {}; }
PeerOut ccdMpr(const Box&, const Box&) { return {}; }
#endif

PeerOut bulletGjkEpa(const Box& a, const Box& b) {
  return isolated([&] {
    // Hulls of the eight corners with zero margin: the exact boxes, as the others get.
    auto hull = [](const Box& box) {
      auto h = std::make_unique<btConvexHullShape>();
      for (int i = 0; i < 8; ++i) {
        const Vec3 c((i & 1) ? box.half.x() : -box.half.x(), (i & 2) ? box.half.y() : -box.half.y(),
                     (i & 4) ? box.half.z() : -box.half.z());
        h->addPoint(btVector3(btScalar(c.x()), btScalar(c.y()), btScalar(c.z())), false);
      }
      h->recalcLocalAabb();
      h->setMargin(0);
      return h;
    };
    auto pose = [](const Box& box) {
      const Mat3& r = box.rotation;
      btMatrix3x3 m(btScalar(r(0, 0)), btScalar(r(0, 1)), btScalar(r(0, 2)), btScalar(r(1, 0)),
                    btScalar(r(1, 1)), btScalar(r(1, 2)), btScalar(r(2, 0)), btScalar(r(2, 1)),
                    btScalar(r(2, 2)));
      return btTransform(m, btVector3(btScalar(box.centre.x()), btScalar(box.centre.y()),
                                      btScalar(box.centre.z())));
    };
    const auto ha = hull(a), hb = hull(b);
    btGjkEpaSolver2::sResults result;
    const bool hit = btGjkEpaSolver2::Penetration(ha.get(), pose(a), hb.get(), pose(b),
                                                  btVector3(1, 0, 0), result);
    if (!hit) return PeerOut{PeerStatus::Apart, 0.0, "reports no penetration"};
    return PeerOut{PeerStatus::Penetrating, -double(result.distance), ""};
  });
}

Cell peerCell(const std::string& row, const std::string& column, const PeerOut& out,
              double truth) {
  Cell c{row, column, "", std::nan(""), std::nan(""), oneLine(out.message)};
  // A peer that gave no answer: its outcome only.
  constexpr std::pair<PeerStatus, const char*> kNoAnswer[] = {{PeerStatus::Missing, "n/a"},
                                                              {PeerStatus::Exception, "exception"},
                                                              {PeerStatus::Crash, "crash"},
                                                              {PeerStatus::Hang, "hang"}};
  for (const auto& [status, outcome] : kNoAnswer) {
    if (out.status != status) continue;
    c.outcome = outcome;
    if (status == PeerStatus::Missing) c.note = "library not found at build time";
    return c;
  }
  c.value = out.status == PeerStatus::Penetrating ? out.depth : std::max(0.0, out.depth);
  if (!std::isfinite(c.value)) {
    c.outcome = "NaN";
    return c;
  }
  c.error = std::abs(c.value - truth);
  if (c.error <= kPassError) c.outcome = "pass";
  else if (out.status == PeerStatus::Apart) c.outcome = "missed";
  else c.outcome = "wrong";
  return c;
}

}  // namespace stab
