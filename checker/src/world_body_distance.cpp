// World::bodySignedDistance (deepcheck/checker/body_distance.h): two bodies' posed pieces from the
// world's current snapshot, measured as unions by geometry::bodySignedDistance, or pairwise when a
// piece is rounded.

#include "deepcheck/checker/body_distance.h"

#include "world_internal.h"

#include "deepcheck/robots/kinematics.h"

#include <algorithm>
#include <limits>
#include <stdexcept>
#include <string>

namespace deepcheck::checker {

using namespace detail;  // NOLINT: the world's own internals

const char* toString(BodyDistanceMethod m) {
  switch (m) {
    case BodyDistanceMethod::Body:
      return "body";
    case BodyDistanceMethod::Pairwise:
      return "pairwise";
  }
  return "unknown";
}

namespace {

/// One side of the query: its pieces in the frame of X_W, and what the contact says about it.
struct PosedBody {
  geometry::Body body;
  Eigen::Isometry3d X_W = Eigen::Isometry3d::Identity();
  int link = -1;  ///< the robot link moving it, -1 for a scene link or obstacle
  std::string name;
  bool rounded = false;  ///< some piece has a radius
};

std::string describe(const BodyRef& b) {
  const char* kinds[] = {"robot link", "scene link", "obstacle", "attached object"};
  return std::string(kinds[static_cast<int>(b.kind)]) + " (index " + std::to_string(b.index) + ", scene " +
         std::to_string(b.scene) + ")";
}

/// The robot geometry (RobotData::links) of a RobotLink or Attached body; throws naming it.
int robotGeometry(const Snapshot& s, const BodyRef& b) {
  const RobotData& robot = *s.robot;
  if (b.index < 0 || b.index >= robot.model.numLinks()) {
    throw std::invalid_argument("bodySignedDistance: no robot link with index " + std::to_string(b.index) + " (" +
                                describe(b) + ")");
  }
  if (b.kind == BodyRef::Kind::Attached &&
      (b.scene < 0 || b.scene >= static_cast<int>(s.attached.size()) || s.attached[b.scene]->link != b.index)) {
    throw std::invalid_argument("bodySignedDistance: no object attached to link " + robot.model.link(b.index).name +
                                " at position " + std::to_string(b.scene) + " of attachedObjects()");
  }
  const int attached = b.kind == BodyRef::Kind::Attached ? b.scene : -1;
  for (int g = 0; g < static_cast<int>(robot.links.size()); ++g) {
    if (robot.links[g].link == b.index && robot.links[g].attached == attached) return g;
  }
  throw std::invalid_argument("bodySignedDistance: the robot link " + robot.model.link(b.index).name +
                              " has no collision geometry");
}

PosedBody robotBody(const Snapshot& s, const std::vector<Eigen::Isometry3d>& X_WL, const BodyRef& b) {
  const RobotData& robot = *s.robot;
  const LinkGeometry& lg = robot.links[robotGeometry(s, b)];
  PosedBody out;
  out.link = lg.link;
  out.X_W = X_WL[lg.link];
  out.name = lg.attached < 0 ? robot.model.link(lg.link).name : "attached/" + s.attached[lg.attached]->source.name;
  for (int i = lg.firstPiece; i < lg.firstPiece + lg.numPieces; ++i) {
    const RobotPiece& p = robot.pieces[i];
    out.body.pieces.push_back({geometry::ConvexShape{p.core.get(), p.radius}, p.X_LP});
    out.rounded = out.rounded || p.radius > 0.0;
  }
  return out;
}

/// A scene link's or an obstacle's pieces, posed in the world (X_W the identity).
PosedBody worldBody(const Snapshot& s, const BodyRef& b) {
  const PieceSet& set = b.kind == BodyRef::Kind::SceneLink ? *s.scenePieces : *s.obstaclePieces;
  PosedBody out;
  for (const WorldPiece& w : set.pieces) {
    if (set.bodies[w.body].ref != b) continue;
    out.name = set.bodies[w.body].name;
    out.body.pieces.push_back({geometry::ConvexShape{w.core.get(), w.radius}, w.X_WP});
    out.rounded = out.rounded || w.radius > 0.0;
  }
  if (!out.body.pieces.empty()) return out;
  if (b.kind == BodyRef::Kind::Obstacle) {
    throw std::invalid_argument("bodySignedDistance: no obstacle with id " + std::to_string(b.index));
  }
  if (b.scene < 0 || b.scene >= static_cast<int>(s.scenes.size()) || b.index < 0 ||
      b.index >= s.scenes[b.scene]->model.numLinks()) {
    throw std::invalid_argument("bodySignedDistance: no such scene link: " + describe(b));
  }
  throw std::invalid_argument("bodySignedDistance: scene/" + s.scenes[b.scene]->model.link(b.index).name +
                              " has no pieces the queries use (no collision geometry, or every piece lies "
                              "beyond the reach filter's margin)");
}

PosedBody posedBody(const Snapshot& s, const std::vector<Eigen::Isometry3d>& X_WL, const BodyRef& b) {
  return b.kind == BodyRef::Kind::RobotLink || b.kind == BodyRef::Kind::Attached ? robotBody(s, X_WL, b)
                                                                                 : worldBody(s, b);
}

/// The minimum over piece pairs (the Pairwise method), as a body result: the answer and the
/// witness pieces; status Separated, Certified (a converged depth) or PairNotCertified.
geometry::BodySignedDistanceResult pairwise(const PosedBody& A, const PosedBody& B,
                                            const geometry::PenetrationOptions& options,
                                            geometry::SignedDistanceStatus* status) {
  geometry::BodySignedDistanceResult out;
  out.distance = std::numeric_limits<double>::infinity();
  for (int i = 0; i < static_cast<int>(A.body.pieces.size()); ++i) {
    const Eigen::Isometry3d X_WA = A.X_W * A.body.pieces[i].X_BP;
    for (int j = 0; j < static_cast<int>(B.body.pieces.size()); ++j) {
      const Eigen::Isometry3d X_WB = B.X_W * B.body.pieces[j].X_BP;
      const geometry::SignedDistanceResult r =
          geometry::signedDistance(A.body.pieces[i].shape, X_WA, B.body.pieces[j].shape, X_WB, nullptr, options);
      if (r.distance < 0.0) ++out.overlappingPairs;
      if (!(r.distance < out.distance)) continue;
      out.distance = r.distance;
      out.normal = r.normal;
      out.pointA = r.pointA;
      out.pointB = r.pointB;
      out.pieceA = i;
      out.pieceB = j;
      *status = r.status;
    }
  }
  const bool converged = *status != geometry::SignedDistanceStatus::NotConverged;
  out.status = out.distance >= 0.0 ? geometry::BodyDepthStatus::Separated
               : converged         ? geometry::BodyDepthStatus::Certified
                                   : geometry::BodyDepthStatus::PairNotCertified;
  out.depthLower = out.depthUpper = -out.distance;
  out.certified = converged;
  out.pairDepth = std::max(-out.distance, 0.0);
  out.pairNormal = out.normal;
  return out;
}

}  // namespace

World::BodyContact World::bodySignedDistance(const Eigen::Ref<const Eigen::VectorXd>& q, const BodyRef& a,
                                             const BodyRef& b) const {
  return bodySignedDistance(q, a, b, BodyDistanceOptions{});
}

World::BodyContact World::bodySignedDistance(const Eigen::Ref<const Eigen::VectorXd>& q, const BodyRef& a,
                                             const BodyRef& b, const BodyDistanceOptions& options) const {
  if (a.kind != BodyRef::Kind::RobotLink && a.kind != BodyRef::Kind::Attached) {
    throw std::invalid_argument("bodySignedDistance: body a must be a robot link or an attached object, got a " +
                                describe(a));
  }
  if (a == b) throw std::invalid_argument("bodySignedDistance: a and b are the same body: " + describe(a));
  const std::shared_ptr<const Snapshot> snap = state_->snapshot();
  const Snapshot& s = *snap;
  const robots::RobotModel& model = s.robot->model;
  const std::vector<Eigen::Isometry3d> X_WL = robots::forwardKinematics(model, q);  // checks q, naming it
  const PosedBody A = posedBody(s, X_WL, a);
  const PosedBody B = posedBody(s, X_WL, b);

  BodyContact out;
  geometry::BodySignedDistanceResult r;
  geometry::SignedDistanceStatus pairStatus = geometry::SignedDistanceStatus::NotConverged;
  if (A.rounded || B.rounded) {
    out.method = BodyDistanceMethod::Pairwise;
    r = pairwise(A, B, options.depth.pair, &pairStatus);
  } else {
    r = geometry::bodySignedDistance(A.body, A.X_W, B.body, B.X_W, options.depth);
    pairStatus = !r.certified        ? geometry::SignedDistanceStatus::NotConverged
                 : r.distance >= 0.0 ? geometry::SignedDistanceStatus::Separated
                                     : geometry::SignedDistanceStatus::Penetrating;
  }
  out.depthStatus = r.status;
  out.depthLower = r.depthLower;
  out.depthUpper = r.depthUpper;
  out.overlappingPairs = r.overlappingPairs;
  out.pairDepth = r.pairDepth;
  out.pairNormal = r.pairNormal;

  Contact& c = out.contact;
  c.distance = r.distance;
  c.normal = r.normal;
  c.pointA = r.pointA;
  c.pointB = r.pointB;
  c.status = pairStatus;
  c.linkA = A.link;
  c.bodyB = b;
  c.nameA = A.name;
  c.nameB = B.name;
  if (options.gradient) {
    // d sd / dq = n^T (J_B(p_B) - J_A(p_A)), the witnesses fixed on their links (world_distance.cpp).
    Eigen::Matrix3Xd J(3, model.numVariables());
    robots::pointJacobian(model, X_WL, A.link, X_WL[A.link].inverse() * r.pointA, J);
    c.gradient = -(J.transpose() * r.normal);
    if (B.link >= 0) {
      robots::pointJacobian(model, X_WL, B.link, X_WL[B.link].inverse() * r.pointB, J);
      c.gradient += J.transpose() * r.normal;
    }
  }
  return out;
}

}  // namespace deepcheck::checker
