// SPDX-License-Identifier: MIT
// FREE on fandisk against armadillo, at poses recorded along BM_HapticPath/0/2
// (bench/penetration_depth.cpp). The twist QP's verdict there was once "no point":
// the NNLS's point missed a row of its own working set by rounding (~1e-9 of the
// rows' magnitudes; FREE's rotation weight, 1e-6 rho^2, spreads the LDP's columns by
// 1e3 / rho), which solvePatchQp took for a wedge, and the proxy stayed where it was
// for hundreds of updates, then caught up in one (a jump of its TPDV). And the slide
// from those poses once ran out of iterations: a capped turn scaled the translation
// down with it, so the proxy crept.
#include <gtest/gtest.h>

#include <Eigen/Geometry>
#include <algorithm>
#include <memory>
#include <vector>

#include "geometry/math_util.h"
#include "penetration/contact_rows.h"
#include "penetration/twist_slide.h"
#include "sc_support/off_mesh.h"
#include "smartcollision/pair_tracker.h"
#include "support/meshes.h"

namespace sc::detail {
namespace {

struct Recorded {
  double rho;
  double proxy[7], previous[7], goal[7];  ///< quaternion w x y z, translation
};

const Recorded kPoses[] = {
    {0.74406454213536521,
     {0.8427109463783693, -0.011975470122389935, -0.53812723212008617, -0.010673847487977575,
      -0.2548679725183976, -0.094878001243066945, -0.53586070124102736},
     {0.84388501803896276, -0.012853020926245708, -0.53623806974267885, -0.011899947104741475,
      -0.25508003450931233, -0.094956940532144873, -0.53630656135479571},
     {0.85354669890029999, -0.015297694984106058, -0.52014731776512002, -0.025899442973262431,
      -0.25486793489912346, -0.094877961670649186, -0.53586062311158578}},
    {0.74406454213536521,
     {0.83332201409646001, 0.042225278633533217, -0.54997695278108072, 0.036287712468276744,
      -0.28685307002199395, -0.082623240072133466, -0.51786606654940059},
     {0.83332201409646001, 0.042225278633533217, -0.54997695278108072, 0.036287712468276744,
      -0.28685307002199395, -0.082623240072133466, -0.51786606654940059},
     {0.85413783414038769, -0.014026404085907183, -0.51911606987120873, -0.027754752383274999,
      -0.28887266324526811, -0.068738775192752843, -0.51590298926901668}},
    {0.74406454213536521,
     {0.83939441132542825, 0.059754453056489, -0.54020341710916009, -0.0051667900240348272,
      -0.28075270391241863, -0.041428050603969264, -0.54408968248069112},
     {0.83939441132542825, 0.059754453056489, -0.54020341710916009, -0.0051667900240348272,
      -0.28075270391241863, -0.041428050603969264, -0.54408968248069112},
     {0.84812546155784929, -0.026443305927070043, -0.52904763805146271, -0.0096202755210563536,
      -0.27129993320044715, -0.037880538840335716, -0.54269999404213165}},
    {0.74406454213536521,
     {0.82594372770048907, 0.052817124833505626, -0.5612535377914144, 0.0046665097422075984,
      -0.24871153304939109, -0.049629932020652932, -0.55002752102122487},
     {0.82594372770048907, 0.052817124833505626, -0.5612535377914144, 0.0046665097422075984,
      -0.24871153304939109, -0.049629932020652932, -0.55002752102122487},
     {0.84443269434043944, -0.033572594759542669, -0.53460794709417481, 0.0008053035512610141,
      -0.23925264829593965, -0.044525315229825994, -0.53341319333748183}},
    {0.74406454213536521,
     {0.82538797415732834, 0.042754253914434839, -0.56213393484507368, 0.030202734715385024,
      -0.23389015746568403, -0.071804788215095922, -0.54188217476102007},
     {0.82538797415732834, 0.042754253914434839, -0.56213393484507368, 0.030202734715385024,
      -0.23389015746568403, -0.071804788215095922, -0.54188217476102007},
     {0.84273593482446429, -0.036739367183344897, -0.53704448205773758, 0.0054394251387548829,
      -0.23181193568177746, -0.06935161723064015, -0.53422425696538922}},
    {0.74406454213536521,
     {0.84141823790154047, 0.045679739148479483, -0.53753497030670594, 0.031382575665183682,
      -0.28954479281160589, -0.077376752986063696, -0.52023662230523982},
     {0.84141823790154047, 0.045679739148479483, -0.53753497030670594, 0.031382575665183682,
      -0.28954479281160589, -0.077376752986063696, -0.52023662230523982},
     {0.85174082723160505, -0.019109567267984674, -0.52321973703106894, -0.020334562862048468,
      -0.28485624663839637, -0.064906398640021623, -0.50709448676862812}},
    {0.74406454213536521,
     {0.82000032071469287, 0.04417863539744897, -0.57019449801469191, 0.022933744483106682,
      -0.2360064806267238, -0.066162033399688208, -0.54407715236203347},
     {0.82000032071469287, 0.04417863539744897, -0.57019449801469191, 0.022933744483106682,
      -0.2360064806267238, -0.066162033399688208, -0.54407715236203347},
     {0.85118906419516682, -0.020253604454006448, -0.52413607865516465, -0.018663856867321416,
      -0.23442600894128071, -0.069968644848470443, -0.53986304029273413}},
    {0.74406454213536521,
     {0.81909088650234751, 0.033592155298714586, -0.57048965658923312, 0.050032374278151583,
      -0.24383641422897651, -0.091757426634148903, -0.52546854042129088},
     {0.81908339776002093, 0.033644615715315553, -0.57050928404190582, 0.04989573297672549,
      -0.24354694186712275, -0.091600050886474688, -0.52565497409412076},
     {0.84718673275585343, -0.028288182707096134, -0.53049645221011721, -0.0069233484724427969,
      -0.24232697458550062, -0.089715307848098266, -0.52075565948283198}},
    {0.74406454213536521,
     {0.84375192074198613, 0.054205162201789135, -0.53388573879804202, 0.010512589737399913,
      -0.28389893629843865, -0.056398264605902956, -0.53503668071884303},
     {0.84375192074198613, 0.054205162201789135, -0.53388573879804202, 0.010512589737399913,
      -0.28389893629843865, -0.056398264605902956, -0.53503668071884303},
     {0.84558424171950197, -0.031385519144851132, -0.53291322740633884, -0.0023940340479642317,
      -0.27470181331493287, -0.038966505664664697, -0.51999738960539588}},
    {0.74406454213536521,
     {0.82594807387935676, 0.053131531003757733, -0.56122355207922747, 0.0038657806176287351,
      -0.24894348540192457, -0.048899074830538992, -0.55035084288332847},
     {0.82594807387935676, 0.053131531003757733, -0.56122355207922747, 0.0038657806176287351,
      -0.24894348540192457, -0.048899074830538992, -0.55035084288332847},
     {0.85113764660315749, -0.020359740216877219, -0.52422095539228752, -0.018508847633960934,
      -0.24418115419334771, -0.043820553590695151, -0.53951466281622573}},
    {0.74406454213536521,
     {0.83251440409708444, 0.035625472742536142, -0.55033463435939289, 0.052748297482478446,
      -0.2583524794208677, -0.094460753982420043, -0.51992803009551103},
     {0.83251440409708444, 0.035625472742536142, -0.55033463435939289, 0.052748297482478446,
      -0.2583524794208677, -0.094460753982420043, -0.51992803009551103},
     {0.85361838289538339, -0.015144167862780286, -0.52002295382051555, -0.02612351550998971,
      -0.26614107155096778, -0.090941787336722577, -0.50982251446170768}},
    {0.74406454213536521,
     {0.83618261740128019, 0.059430202781581606, -0.54519036655978792, -0.005843420550514615,
      -0.28037080968564398, -0.041193088481194302, -0.54412268422909604},
     {0.83618262036734048, 0.059429926030029799, -0.54519039672803615, -0.0058429960843466768,
      -0.28070833617791413, -0.041227993386858362, -0.54397504108660366},
     {0.84423820509356695, -0.0339389013700305, -0.53489083475522692, 0.0013412416055041424,
      -0.27994442206885178, -0.040200569240742723, -0.54291461690816767}},
};

Rigid rigidOf(const double* v) {
  return {Eigen::Quaterniond(v[0], v[1], v[2], v[3]).normalized().toRotationMatrix(),
          Vec3(v[4], v[5], v[6])};
}

ModelPtr unitModel(const std::string& name) {
  MeshData mesh = support::fitToSize(test::loadTestMesh(name), 1.0);
  if (mesh.triangles.empty()) return nullptr;
  auto piece = buildPiece(ModelKind::ClosedPolyhedron, mesh);
  if (!piece.ok()) return nullptr;
  return std::make_shared<Model>(ModelKind::ClosedPolyhedron, std::vector<PiecePtr>{piece.value()});
}

TEST(FreePatchQp, RoundingInTheWorkingSetIsNotAWedge) {
  const ModelPtr fandisk = unitModel("fandisk"), armadillo = unitModel("armadillo");
  ASSERT_TRUE(fandisk && armadillo);
  const Part t_part{fandisk.get(), Rigid(), 0}, o_part{armadillo.get(), Rigid(), 1};
  GroupPairQuery q;
  q.bind(GroupView{&t_part, 1, Placement()}, GroupView{&o_part, 1, Placement()});
  PairSettings settings;
  settings.rotation_mode = RotationMode::Free;
  const double skin = 0.25 * settings.tolerance;  // the proxy's (proxy_tracker.cpp)
  const Vec3 center = Vec3::Zero();
  for (const Recorded& r : kPoses) {
    const Rigid proxy = rigidOf(r.proxy), previous = rigidOf(r.previous), goal = rigidOf(r.goal);
    std::vector<LeafContact> contacts;
    q.contacts(proxy, settings.tolerance, contacts);
    ASSERT_FALSE(contacts.empty());
    std::vector<ContactPatch> patches;
    buildContactPatches(q, proxy, contacts, previous, patches);
    const Vec3 y = proxy * center;
    Eigen::Matrix<double, 6, 1> target;
    target << goal * center - y, rotationVector(goal.rotation * proxy.rotation.transpose());
    PatchQpWork work;
    solvePatchQp(patches, y, target, twistWeights(settings, targetRadius(q, center)), skin,
                 settings.tolerance, work);
    ASSERT_TRUE(work.qp.feasible) << "pose " << (&r - kPoses);
    // The point keeps every row (all of buildContactRows', not only the working set)
    // to far below the skin.
    std::vector<ContactRow> rows;
    buildContactRows(q, proxy, y, contacts, previous, rows, settings.tolerance);
    const Eigen::Matrix<double, 6, 1> z = work.qp.z;
    for (const ContactRow& row : rows) {
      const double slack = row.normal.dot(z.head<3>()) +
                           row.lever.cross(row.normal).dot(z.tail<3>()) + row.gap - skin;
      EXPECT_GT(slack, -1e-6 * skin) << "pose " << (&r - kPoses);
    }
  }
}

/// Slerp and lerp between two poses.
Rigid between(const Rigid& a, const Rigid& b, double t) {
  const Eigen::Quaterniond qa(a.rotation), qb(b.rotation);
  return {qa.slerp(t, qb).toRotationMatrix(), (1.0 - t) * a.translation + t * b.translation};
}

TEST(FreeSlide, UpdatesSettleWithinTheirIterations) {
  // The target pushed from a recorded free proxy through its goal and twice as far
  // again, in 60 steps: FREE's nearly free rotation asks for turns far above the cap
  // while the proxy rests on a few patches. Each update must settle within the
  // default 30 iterations (not lag), at the depth a tracker with 2000 iterations per
  // update reports.
  const ModelPtr fandisk = unitModel("fandisk"), armadillo = unitModel("armadillo");
  ASSERT_TRUE(fandisk && armadillo);
  const Part t_part{fandisk.get(), Rigid(), 0}, o_part{armadillo.get(), Rigid(), 1};
  PairSettings settings;
  settings.rotation_mode = RotationMode::Free;
  PairSettings patient = settings;
  patient.max_iterations = 2000;
  auto update = [&](PairTracker& tracker, const Rigid& pose, const PairSettings& s) {
    GroupView target{&t_part, 1, Placement()};
    target.placement.setMatrix(pose.rotation, pose.translation);
    DirectedResult out[2];
    tracker.update(target, GroupView{&o_part, 1, Placement()}, Directions{true, false}, s, out);
    return out[0];
  };
  int lagging = 0, penetrating = 0;
  double worst = 0.0;
  for (const Recorded& r : {kPoses[1], kPoses[5], kPoses[9]}) {
    const Rigid from = rigidOf(r.previous), to = rigidOf(r.goal);
    PairTracker fast, slow;
    for (int k = 0; k <= 60; ++k) {
      const Rigid pose = between(from, to, k / 30.0);
      const DirectedResult a = update(fast, pose, settings), b = update(slow, pose, patient);
      ASSERT_EQ(a.code, ErrorCode::Ok);
      ASSERT_EQ(b.code, ErrorCode::Ok);
      lagging += a.status == DirectionStatus::Lagging;
      penetrating += a.hasDepth();
      worst = std::max(worst, (a.tpdv - b.tpdv).norm());
    }
  }
  EXPECT_GT(penetrating, 60);
  EXPECT_EQ(lagging, 0);
  EXPECT_LT(worst, 1e-2 * settings.tolerance);
}

}  // namespace
}  // namespace sc::detail
