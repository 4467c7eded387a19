// Push-out by damped least squares over all contacts, and the random-jiggle baseline
// (see push_out.h for the method and its departures from a textbook projection).

#include "deepcheck/planners/push_out.h"

#include "deepcheck/checker/body_distance.h"

#include "deepcheck/robots/format_number.h"
#include "deepcheck/robots/joint_angles.h"
#include "deepcheck/robots/kinematics.h"
#include "deepcheck/robots/random_configuration.h"

#include <Eigen/Cholesky>

#include <algorithm>
#include <cmath>
#include <cstdio>
#include <limits>
#include <stdexcept>
#include <string>
#include <vector>

namespace deepcheck::planners {

namespace {

using robots::uniform01;

/// One pair the push-out watches: its distance and gradient at the current iterate.
struct Row {
  int linkA = -1;
  checker::BodyRef bodyB;
  double distance = 0.0;
  Eigen::VectorXd gradient;
};

/// One damped-least-squares step within the joint limits (push_out.h, steps 2 and 3), with the
/// rows farther than the target joining the constraints when the step would bring them inside it.
Eigen::VectorXd limitedStep(const std::vector<Row>& rows, double target, const Eigen::VectorXd& q,
                            const Eigen::VectorXd& lower, const Eigen::VectorXd& upper, const PushOutOptions& options) {
  const int n = static_cast<int>(q.size());
  const int m = static_cast<int>(rows.size());
  std::vector<bool> active(static_cast<std::size_t>(m));
  for (int i = 0; i < m; ++i)
    active[static_cast<std::size_t>(i)] = rows[static_cast<std::size_t>(i)].distance <= target;
  std::vector<bool> fixed(static_cast<std::size_t>(n), false);
  Eigen::VectorXd dq = Eigen::VectorXd::Zero(n);  // the clipped joints' motion onto their limits
  Eigen::VectorXd step = Eigen::VectorXd::Zero(n);
  const double lambda2 = options.damping * options.damping;
  for (int round = 0; round <= n + m; ++round) {
    std::vector<int> freeJoints;
    std::vector<int> activeRows;
    for (int j = 0; j < n; ++j) {
      if (!fixed[static_cast<std::size_t>(j)]) freeJoints.push_back(j);
    }
    for (int i = 0; i < m; ++i) {
      if (active[static_cast<std::size_t>(i)]) activeRows.push_back(i);
    }
    step = dq;
    if (freeJoints.empty() || activeRows.empty()) break;
    const int k = static_cast<int>(freeJoints.size());
    const int a = static_cast<int>(activeRows.size());
    Eigen::MatrixXd A(a, k);
    Eigen::VectorXd rhs(a);
    for (int r = 0; r < a; ++r) {
      const Row& row = rows[static_cast<std::size_t>(activeRows[static_cast<std::size_t>(r)])];
      for (int c = 0; c < k; ++c) A(r, c) = row.gradient[freeJoints[static_cast<std::size_t>(c)]];
      // The clipped joints already move this pair by gradient . dq.
      rhs[r] = target - row.distance - row.gradient.dot(dq);
    }
    Eigen::MatrixXd M = A * A.transpose();
    M.diagonal().array() += lambda2;
    Eigen::VectorXd dFree = A.transpose() * M.ldlt().solve(rhs);
    const double largest = dFree.cwiseAbs().maxCoeff();
    if (largest > options.maxJointStep) dFree *= options.maxJointStep / largest;
    for (int c = 0; c < k; ++c) step[freeJoints[static_cast<std::size_t>(c)]] = dFree[c];

    bool changed = false;
    for (int c = 0; c < k; ++c) {
      const int j = freeJoints[static_cast<std::size_t>(c)];
      const double next = q[j] + step[j];
      if (next < lower[j] || next > upper[j]) {
        dq[j] = std::clamp(next, lower[j], upper[j]) - q[j];
        fixed[static_cast<std::size_t>(j)] = true;
        changed = true;
      }
    }
    for (int i = 0; i < m; ++i) {
      const Row& row = rows[static_cast<std::size_t>(i)];
      if (!active[static_cast<std::size_t>(i)] && row.distance + row.gradient.dot(step) < target) {
        active[static_cast<std::size_t>(i)] = true;
        changed = true;
      }
    }
    if (!changed) break;
  }
  return step;
}

/// The state of one PushOut::run past its trivial exits: the distance query at the iterate, the
/// bundle of linearizations made at other iterates, and the pattern search.
class PushOutSearch {
 public:
  PushOutSearch(const checker::World& world, const ValidityOptions& validity, const PushOutOptions& options,
                Eigen::Index size)
      : world_(world),
        validity_(validity),
        options_(options),
        lower_(world.robot().lowerLimits()),
        upper_(world.robot().upperLimits()),
        size_(size),
        target_(validity.threshold() + options.targetClearance),
        watch_(target_ + tol::kPushOutLookahead) {}

  /// The contacts within the watched distance, with gradients; with options.bodyDepth the
  /// overlapping ones measured as bodies (useBodyDepth).
  checker::DistanceResult query(const Eigen::VectorXd& q) const {
    checker::DistanceOptions options;
    options.gradient = true;
    options.contactMargin = watch_;
    options.maxDistance = std::max(watch_, 0.0) + tol::kDistanceCapMargin;
    checker::DistanceResult d = world_.signedDistance(q, options);
    if (options_.bodyDepth && bodyQueries_ < tol::kPushOutMaxBodyQueries) useBodyDepth(q, d);
    return d;
  }
  /// The minimum distance at q as the search judges it: the pairwise one up to the watched
  /// distance, or with options.bodyDepth the minimum of query(q).
  double distanceAt(const Eigen::VectorXd& q) const {
    return options_.bodyDepth ? minimum(query(q)) : signedDistanceUpTo(world_, q, watch_);
  }
  /// True once a body-depth search has made tol::kPushOutMaxBodyQueries body queries: it then
  /// stops (and the pairwise search takes over, PushOut::retryPairwise).
  bool bodyQueriesSpent() const { return options_.bodyDepth && bodyQueries_ >= tol::kPushOutMaxBodyQueries; }
  /// How far contacts are watched (metres): the minimum distance when nothing is nearer.
  double watched() const { return watch_; }
  /// The minimum distance of a query (the watched distance when nothing is nearer).
  double minimum(const checker::DistanceResult& d) const { return d.found ? d.closest.distance : watch_; }

  /// Iterates from `result->q` (whose query is `d`) until it is valid or the iterations are
  /// spent; sets result's q and iterations, returns true when q is valid.
  bool iterate(checker::DistanceResult d, PushOutResult* result);

 private:
  /// Replaces every overlapping contact whose A is a robot link by the body answer of its pair
  /// (distance, normal, witnesses, gradient), and the closest pair by the smallest of them. A
  /// contact of an attached object, or one whose body query hit its build cap, keeps its pairwise
  /// answer.
  void useBodyDepth(const Eigen::VectorXd& q, checker::DistanceResult& d) const {
    checker::World::BodyDistanceOptions options;
    options.gradient = true;
    options.depth.maxBuildCost = options_.bodyBuildCost;
    for (checker::Contact& c : d.contacts) {
      if (!(c.distance < 0.0) || c.linkA < 0 || c.nameA != world_.robot().link(c.linkA).name) continue;
      checker::BodyRef a;
      a.kind = checker::BodyRef::Kind::RobotLink;
      a.index = c.linkA;
      ++bodyQueries_;
      checker::World::BodyContact answer = world_.bodySignedDistance(q, a, c.bodyB, options);
      if (answer.depthStatus == geometry::BodyDepthStatus::BuildLimit) continue;  // too costly: pairwise
      checker::Contact& body = answer.contact;
      c.distance = body.distance;
      c.normal = body.normal;
      c.pointA = body.pointA;
      c.pointB = body.pointB;
      c.status = body.status;
      c.gradient = std::move(body.gradient);
      if (c.distance < d.closest.distance) d.closest = c;
    }
  }

  mutable int bodyQueries_ = 0;  ///< body queries made so far (one per overlapping contact measured)

  /// Linearizations made at other iterates (the bundle), newest last.
  struct Cut {
    Row row;
    Eigen::VectorXd at;
  };

  void remember(const checker::DistanceResult& dAt, const Eigen::VectorXd& at) {
    for (const checker::Contact& c : dAt.contacts) {
      if (c.gradient.size() == size_) bundle_.push_back(Cut{Row{c.linkA, c.bodyB, c.distance, c.gradient}, at});
    }
    if (bundle_.size() > static_cast<std::size_t>(tol::kPushOutBundleSize)) {
      bundle_.erase(bundle_.begin(), bundle_.end() - tol::kPushOutBundleSize);
    }
  }

  /// The constraints at q: the contacts of its query `d`, and the bundle's cuts near q
  /// linearized at q.
  std::vector<Row> rowsAt(const checker::DistanceResult& d, const Eigen::VectorXd& q) const {
    std::vector<Row> rows;
    for (const checker::Contact& c : d.contacts) {
      if (c.gradient.size() == size_) rows.push_back(Row{c.linkA, c.bodyB, c.distance, c.gradient});
    }
    for (const Cut& cut : bundle_) {
      const Eigen::VectorXd offset = q - cut.at;
      if (offset.cwiseAbs().maxCoeff() > tol::kPushOutBundleRadius) continue;
      Row row = cut.row;
      row.distance += row.gradient.dot(offset);  // the cut's linearization, evaluated here
      rows.push_back(std::move(row));
    }
    return rows;
  }

  /// Pattern search (see tol::kPushOutProbeSteps): the smallest single-joint move that makes q
  /// valid (then `isValid`), else the one that improves the minimum distance most. False when
  /// none improves. `d`: q's query.
  bool probe(const checker::DistanceResult& d, Eigen::VectorXd& q, bool& isValid) const {
    const double current = minimum(d);
    double best = current;
    Eigen::VectorXd bestQ;
    for (double size : tol::kPushOutProbeSteps) {
      for (Eigen::Index j = 0; j < size_; ++j) {
        for (double sign : {1.0, -1.0}) {
          Eigen::VectorXd candidate = q;
          candidate[j] = std::clamp(candidate[j] + sign * size, lower_[j], upper_[j]);
          if (candidate[j] == q[j]) continue;
          const double sd = distanceAt(candidate);
          if (sd > validity_.threshold() && isConfigurationValid(world_, candidate, validity_)) {
            q = candidate;
            isValid = true;
            return true;
          }
          if (sd > best) {
            best = sd;
            bestQ = candidate;
          }
        }
      }
    }
    if (!(best > current)) return false;
    q = bestQ;
    return true;
  }

  const checker::World& world_;
  const ValidityOptions& validity_;
  const PushOutOptions& options_;
  const Eigen::VectorXd& lower_;
  const Eigen::VectorXd& upper_;
  const Eigen::Index size_;
  const double target_;
  const double watch_;
  std::vector<Cut> bundle_;
};

bool PushOutSearch::iterate(checker::DistanceResult d, PushOutResult* result) {
  int rejected = 0;  // consecutive steps that made the minimum distance worse
  int stalled = 0;   // iterations without kPushOutStallImprovement
  double bestMinimum = minimum(d);
  bool valid = false;
  for (int iteration = 0; iteration < options_.maxIterations && !valid && !bodyQueriesSpent(); ++iteration) {
    result->iterations = iteration + 1;
    const std::vector<Row> rows = rowsAt(d, result->q);
    const Eigen::VectorXd dq =
        rows.empty() ? Eigen::VectorXd::Zero(size_) : limitedStep(rows, target_, result->q, lower_, upper_, options_);
    if (!(dq.cwiseAbs().maxCoeff() > 0.0) || stalled >= tol::kPushOutStallIterations) {
      // No step from the gradients (every useful joint on its limit, or a flat distance), or no
      // progress: probe single joints.
      if (!probe(d, result->q, valid)) break;
      if (valid) break;
      bundle_.clear();
      stalled = 0;
      rejected = 0;
      d = query(result->q);
      bestMinimum = minimum(d);
      continue;
    }
    const Eigen::VectorXd next = result->q + dq;
    if (isConfigurationValid(world_, next, validity_)) {
      result->q = next;
      valid = true;
      break;
    }
    checker::DistanceResult dNext = query(next);
    if (minimum(dNext) < minimum(d) && rejected < 2) {
      // Worse than before: stay, but keep what was learned there (its gradients) for the next try.
      ++rejected;
      ++stalled;
      remember(dNext, next);
      continue;
    }
    rejected = 0;
    remember(d, result->q);
    result->q = next;
    d = std::move(dNext);
    if (minimum(d) > bestMinimum + tol::kPushOutStallImprovement) {
      bestMinimum = minimum(d);
      stalled = 0;
    } else {
      ++stalled;
    }
  }
  return valid;
}

}  // namespace

const char* toString(PushOutStatus status) {
  switch (status) {
    case PushOutStatus::AlreadyValid:
      return "AlreadyValid";
    case PushOutStatus::Repaired:
      return "Repaired";
    case PushOutStatus::TooDeep:
      return "TooDeep";
    case PushOutStatus::NotConverged:
      return "NotConverged";
  }
  return "?";
}

void checkPushOutOptions(const PushOutOptions& options) {
  auto positive = [](double v, const char* name) {
    if (!(v > 0.0) || std::isnan(v)) {
      throw std::invalid_argument(std::string("PushOutOptions: ") + name + " must be > 0, got " +
                                  robots::formatNumber(v));
    }
  };
  positive(options.targetClearance, "targetClearance");
  positive(options.damping, "damping");
  positive(options.maxJointStep, "maxJointStep");
  positive(options.maxDepth, "maxDepth");
  if (!(options.bodyBuildCost >= 0.0)) {
    throw std::invalid_argument("PushOutOptions: bodyBuildCost must be >= 0 (infinity for no cap), got " +
                                robots::formatNumber(options.bodyBuildCost));
  }
  if (!std::isfinite(options.targetClearance) || !std::isfinite(options.damping) ||
      !std::isfinite(options.maxJointStep)) {
    throw std::invalid_argument("PushOutOptions: targetClearance, damping and maxJointStep must be finite");
  }
  if (options.maxIterations < 1) {
    throw std::invalid_argument("PushOutOptions: maxIterations must be >= 1, got " +
                                std::to_string(options.maxIterations));
  }
}

PushOut::PushOut(std::shared_ptr<const checker::World> world, const ValidityOptions& validity,
                 const PushOutOptions& options)
    : world_(std::move(world)), validity_(validity), options_(options) {
  if (!world_) throw std::invalid_argument("PushOut: the world is null");
  checkValidityOptions(validity_);
  checkPushOutOptions(options_);
}

PushOut standOffPushOut(std::shared_ptr<const checker::World> world, const ValidityOptions& validity,
                        const PushOutOptions& options, double standOff) {
  if (!std::isfinite(standOff) || standOff < 0.0) {
    throw std::invalid_argument("standOffPushOut: the stand-off must be finite and >= 0 metres, got " +
                                robots::formatNumber(standOff));
  }
  // Only the difference of the two options matters (validity.h): move the threshold up by standOff.
  const double threshold = validity.threshold() + standOff;
  ValidityOptions raised;
  raised.safetyMargin = std::max(threshold, 0.0);
  raised.penetrationTolerance = std::max(-threshold, 0.0);
  return PushOut(std::move(world), raised, options);
}

namespace {

/// PushOutResult::reason: the first pair that no joint moves and that makes every configuration
/// invalid (sd <= threshold), or "".
std::string blockingFixedPair(const checker::World& world, double threshold) {
  const std::vector<checker::Contact> fixed = world.fixedPairs(threshold);
  if (fixed.empty()) return "";
  const checker::Contact& c = fixed.front();
  char distance[32];
  std::snprintf(distance, sizeof distance, "%.3g", c.distance);
  return "the link " + world.robot().link(c.linkA).name + " is moved by no joint, and " + c.nameA + " is " + distance +
         " m from " + c.nameB + " in every configuration (at most the validity threshold " +
         robots::formatNumber(threshold) +
         " m): no push-out can repair it; allow the pair if it is meant to touch: --allow-collision " + c.nameA + ":" +
         c.nameB + " (checker::World::allowCollision)";
}

}  // namespace

bool PushOut::retryPairwise(const Eigen::VectorXd& start, PushOutResult& result) const {
  PushOutOptions pairwise = options_;
  pairwise.bodyDepth = false;
  PushOutSearch search(*world_, validity_, pairwise, start.size());
  PushOutResult retry = result;
  retry.q = start;
  retry.iterations = 0;
  const bool valid = search.iterate(search.query(start), &retry);
  const int spent = result.iterations + retry.iterations;
  if (valid) result.q = retry.q;
  result.iterations = spent;
  return valid;
}

PushOutResult PushOut::run(const Eigen::Ref<const Eigen::VectorXd>& given) const {
  const robots::RobotModel& model = world_->robot();
  robots::checkConfiguration(model, given);
  // A wrapping variable's value is an angle (4.0 rad is 4.0 - 2 pi), not clamped to pi below.
  Eigen::VectorXd q0 = given;
  robots::normalizeWrappingVariables(model, q0);
  const Eigen::VectorXd& lower = model.lowerLimits();
  const Eigen::VectorXd& upper = model.upperLimits();

  PushOutResult result;
  result.q = q0.cwiseMax(lower).cwiseMin(upper);
  result.initialDistance = std::numeric_limits<double>::quiet_NaN();
  result.finalDistance = std::numeric_limits<double>::quiet_NaN();
  const bool clamped = result.q != q0;
  if (isConfigurationValid(*world_, result.q, validity_)) {
    result.status = clamped ? PushOutStatus::Repaired : PushOutStatus::AlreadyValid;
    result.jointMotion = (result.q - q0).norm();
    return result;
  }

  PushOutSearch search(*world_, validity_, options_, q0.size());
  checker::DistanceResult d = search.query(result.q);
  result.initialDistance = search.minimum(d);
  // The gate is the deepest pair's depth whichever depth the search steps by, so that the body
  // depth (never shallower) turns no start away that the pairwise search would take.
  const double gateDistance =
      options_.bodyDepth ? signedDistanceUpTo(*world_, result.q, search.watched()) : result.initialDistance;
  if (gateDistance < -options_.maxDepth) {
    result.reason = blockingFixedPair(*world_, validity_.threshold());
    result.status = PushOutStatus::TooDeep;
    result.q = q0;
    result.finalDistance = result.initialDistance;
    return result;
  }
  const Eigen::VectorXd start = result.q;
  bool valid = search.iterate(std::move(d), &result);
  if (!valid && options_.bodyDepth) valid = retryPairwise(start, result);
  result.status = valid ? PushOutStatus::Repaired : PushOutStatus::NotConverged;
  if (!valid) result.reason = blockingFixedPair(*world_, validity_.threshold());
  result.jointMotion = (result.q - q0).norm();
  result.finalDistance = signedDistanceUpTo(*world_, result.q, std::numeric_limits<double>::infinity());
  return result;
}

PushOutResult jiggle(const checker::World& world, const ValidityOptions& validity,
                     const Eigen::Ref<const Eigen::VectorXd>& q, const JiggleOptions& options, std::mt19937_64& rng) {
  checkValidityOptions(validity);
  if (!(options.fraction > 0.0) || !std::isfinite(options.fraction)) {
    throw std::invalid_argument("JiggleOptions: fraction must be finite and > 0, got " +
                                robots::formatNumber(options.fraction));
  }
  if (options.attempts < 1) {
    throw std::invalid_argument("JiggleOptions: attempts must be >= 1, got " + std::to_string(options.attempts));
  }
  const robots::RobotModel& model = world.robot();
  robots::checkConfiguration(model, q);
  const Eigen::VectorXd& lower = model.lowerLimits();
  const Eigen::VectorXd& upper = model.upperLimits();

  PushOutResult result;
  result.q = q;
  result.initialDistance = std::numeric_limits<double>::quiet_NaN();
  result.finalDistance = std::numeric_limits<double>::quiet_NaN();
  if (q.cwiseMax(lower).cwiseMin(upper) == q && isConfigurationValid(world, q, validity)) {
    result.status = PushOutStatus::AlreadyValid;
    return result;
  }
  Eigen::VectorXd candidate(q.size());
  for (int attempt = 1; attempt <= options.attempts; ++attempt) {
    for (Eigen::Index j = 0; j < q.size(); ++j) {
      const double half = options.fraction * (upper[j] - lower[j]);
      candidate[j] = std::clamp(q[j] + (2.0 * uniform01(rng) - 1.0) * half, lower[j], upper[j]);
    }
    result.iterations = attempt;
    if (isConfigurationValid(world, candidate, validity)) {
      result.status = PushOutStatus::Repaired;
      result.q = candidate;
      result.jointMotion = (candidate - q).norm();
      result.finalDistance = signedDistanceUpTo(world, candidate, std::numeric_limits<double>::infinity());
      return result;
    }
  }
  result.status = PushOutStatus::NotConverged;
  return result;
}

double maxLinkDisplacement(const robots::RobotModel& model, const Eigen::Ref<const Eigen::VectorXd>& a,
                           const Eigen::Ref<const Eigen::VectorXd>& b) {
  const std::vector<Eigen::Isometry3d> X_a = robots::forwardKinematics(model, a);
  const std::vector<Eigen::Isometry3d> X_b = robots::forwardKinematics(model, b);
  double largest = 0.0;
  for (std::size_t i = 0; i < X_a.size(); ++i) {
    largest = std::max(largest, (X_a[i].translation() - X_b[i].translation()).norm());
  }
  return largest;
}

}  // namespace deepcheck::planners
