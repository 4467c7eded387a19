#include "deepcheck/planners/motion_bound.h"

#include <algorithm>
#include <cmath>
#include <stdexcept>
#include <string>

namespace deepcheck::planners {

namespace {

void checkBoundInputs(const robots::RobotModel& model, const std::vector<double>& linkExtent,
                      const std::vector<std::pair<int, int>>& selfPairs) {
  const int numLinks = model.numLinks();
  if (static_cast<int>(linkExtent.size()) != numLinks) {
    throw std::invalid_argument("LinkSpeedBound: " + std::to_string(linkExtent.size()) + " link extents for robot '" +
                                model.name() + "' with " + std::to_string(numLinks) + " links");
  }
  for (const auto& [a, b] : selfPairs) {
    if (a < 0 || b < 0 || a >= numLinks || b >= numLinks) {
      throw std::invalid_argument("LinkSpeedBound: self pair (" + std::to_string(a) + ", " + std::to_string(b) +
                                  ") names a link robot '" + model.name() + "' does not have");
    }
  }
  for (int i = 0; i < numLinks; ++i) {
    const double rho = linkExtent[static_cast<std::size_t>(i)];
    if (std::isnan(rho) || std::isinf(rho)) {
      throw std::invalid_argument("LinkSpeedBound: link '" + model.link(i).name + "' has a non-finite extent");
    }
  }
}

/// Adds to `speed` (one row per variable) how fast the points of link i, within `extent` of its
/// origin, move per unit of each variable, walking up its chain.
void addLinkSpeed(const robots::RobotModel& model, int i, double extent, Eigen::RowVectorXd& speed) {
  // `reach` bounds |p - o| for the points p of link i and the origin o of the joint frame
  // reached so far.
  double reach = extent;
  int link = i;
  while (model.link(link).parentJoint >= 0) {
    const robots::Joint& joint = model.joint(model.link(link).parentJoint);
    double travel = 0.0;
    if (joint.moves() && joint.variable >= 0) {
      const double m = std::abs(joint.multiplier);
      if (joint.type == robots::JointType::Prismatic) {
        speed[joint.variable] += m;
        const double lo = joint.multiplier * model.lowerLimits()[joint.variable] + joint.offset;
        const double hi = joint.multiplier * model.upperLimits()[joint.variable] + joint.offset;
        travel = std::max(std::abs(lo), std::abs(hi));
      } else {
        speed[joint.variable] += m * reach;
      }
    }
    reach += joint.X_PJ.translation().norm() + travel;
    link = joint.parentLink;
  }
}

/// The nearest common ancestor of links a and b (the root at worst).
int commonAncestor(const robots::RobotModel& model, int a, int b) {
  std::vector<int> chainB;  // b, its parent, ..., the root
  for (int l = b; l >= 0; l = model.link(l).parentLink) chainB.push_back(l);
  for (int l = a; l >= 0; l = model.link(l).parentLink) {
    if (std::find(chainB.begin(), chainB.end(), l) != chainB.end()) return l;
  }
  return 0;
}

/// Adds to `row` the speeds of `link` in the variables that move it relative to `ancestor`.
void addRelativeSpeed(const robots::RobotModel& model, const Eigen::MatrixXd& speed, int link, int ancestor,
                      Eigen::RowVectorXd& row) {
  const int n = model.numVariables();
  std::vector<bool> moves(static_cast<std::size_t>(n), false);
  for (int l = link; l != ancestor; l = model.link(l).parentLink) {
    const robots::Joint& joint = model.joint(model.link(l).parentJoint);
    if (joint.moves() && joint.variable >= 0) moves[static_cast<std::size_t>(joint.variable)] = true;
  }
  for (int v = 0; v < n; ++v) {
    if (moves[static_cast<std::size_t>(v)]) row[v] += speed(link, v);
  }
}

}  // namespace

LinkSpeedBound::LinkSpeedBound(const robots::RobotModel& model, const std::vector<double>& linkExtent,
                               std::vector<std::pair<int, int>> selfPairs)
    : extent_(linkExtent), selfPairs_(std::move(selfPairs)) {
  checkBoundInputs(model, linkExtent, selfPairs_);
  const int numLinks = model.numLinks();
  const int n = model.numVariables();
  speed_ = Eigen::MatrixXd::Zero(numLinks, n);
  for (int i = 0; i < numLinks; ++i) {
    const double rho = linkExtent[static_cast<std::size_t>(i)];
    if (rho < 0.0) continue;  // no geometry
    geometryLinks_.push_back(i);
    Eigen::RowVectorXd row = Eigen::RowVectorXd::Zero(n);
    addLinkSpeed(model, i, rho, row);
    speed_.row(i) = row;
  }
  // Self pairs: the variables that move each link relative to the pair's common ancestor.
  selfSpeed_ = Eigen::MatrixXd::Zero(static_cast<Eigen::Index>(selfPairs_.size()), n);
  selfPairRow_ = Eigen::MatrixXi::Constant(numLinks, numLinks, -1);
  for (std::size_t p = 0; p < selfPairs_.size(); ++p) {
    const auto [a, b] = selfPairs_[p];
    const int common = commonAncestor(model, a, b);
    Eigen::RowVectorXd row = Eigen::RowVectorXd::Zero(n);
    addRelativeSpeed(model, speed_, a, common, row);
    addRelativeSpeed(model, speed_, b, common, row);
    selfSpeed_.row(static_cast<Eigen::Index>(p)) = row;
    selfPairRow_(a, b) = static_cast<int>(p);
    selfPairRow_(b, a) = static_cast<int>(p);
  }
}

LinkSpeedBound LinkSpeedBound::forWorld(const checker::World& world) {
  return LinkSpeedBound(world.robot(), world.linkExtents(), world.allowedSelfPairs());
}

void LinkSpeedBound::displacements(const Eigen::Ref<const Eigen::VectorXd>& dq, Eigen::VectorXd& link,
                                   Eigen::MatrixXd& self) const {
  checkMotion(dq);
  // Called for every motion a planner checks: the scratch is the thread's, made once.
  thread_local Eigen::VectorXd magnitude;
  magnitude = dq.cwiseAbs();
  link.noalias() = speed_ * magnitude;
  const Eigen::Index n = link.size();
  self.resize(n, n);
  for (Eigen::Index b = 0; b < n; ++b) {
    for (Eigen::Index a = 0; a < n; ++a) self(a, b) = link[a] + link[b];
  }
  for (std::size_t p = 0; p < selfPairs_.size(); ++p) {
    const auto [a, b] = selfPairs_[p];
    self(a, b) = self(b, a) = selfSpeed_.row(static_cast<Eigen::Index>(p)).dot(magnitude);
  }
}

double LinkSpeedBound::linkDisplacement(int link, const Eigen::Ref<const Eigen::VectorXd>& dq) const {
  if (link < 0 || link >= speed_.rows()) {
    throw std::invalid_argument("LinkSpeedBound::linkDisplacement: no link " + std::to_string(link));
  }
  checkMotion(dq);
  return speed_.row(link).dot(dq.cwiseAbs());
}

void LinkSpeedBound::checkMotion(const Eigen::Ref<const Eigen::VectorXd>& dq) const {
  if (dq.size() != speed_.cols()) {
    throw std::invalid_argument("LinkSpeedBound: a motion of " + std::to_string(dq.size()) + " values for " +
                                std::to_string(speed_.cols()) + " variables");
  }
}

double LinkSpeedBound::pairDisplacement(const Eigen::Ref<const Eigen::VectorXd>& dq) const {
  checkMotion(dq);
  const Eigen::VectorXd magnitude = dq.cwiseAbs();
  const Eigen::VectorXd D = speed_ * magnitude;
  double bound = 0.0;
  for (int i : geometryLinks_) bound = std::max(bound, D[i]);
  if (selfSpeed_.rows() > 0) bound = std::max(bound, (selfSpeed_ * magnitude).maxCoeff());
  return bound;
}

double LinkSpeedBound::pairDisplacement(int linkA, int linkB, const Eigen::Ref<const Eigen::VectorXd>& dq) const {
  checkMotion(dq);
  const int numLinks = static_cast<int>(speed_.rows());
  if (linkA < 0 || linkA >= numLinks || linkB >= numLinks) {
    throw std::invalid_argument("LinkSpeedBound::pairDisplacement: no pair (" + std::to_string(linkA) + ", " +
                                std::to_string(linkB) + ")");
  }
  if (linkB < 0) return speed_.row(linkA).dot(dq.cwiseAbs());
  const int row = selfPairRow_(linkA, linkB);
  if (row < 0) return (speed_.row(linkA) + speed_.row(linkB)).dot(dq.cwiseAbs());
  return selfSpeed_.row(row).dot(dq.cwiseAbs());
}

}  // namespace deepcheck::planners
