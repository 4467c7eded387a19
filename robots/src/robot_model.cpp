#include "deepcheck/robots/robot_model.h"

#include "deepcheck/robots/format_number.h"
#include "deepcheck/robots/package_path.h"
#include "deepcheck/robots/tolerances.h"

#include "urdf_prepass.h"
#include "in_quotes.h"

#include <console_bridge/console.h>
#include <urdf_parser/urdf_parser.h>

#include <algorithm>
#include <cmath>
#include <cstdlib>
#include <filesystem>
#include <fstream>
#include <map>
#include <mutex>
#include <set>
#include <sstream>
#include <stdexcept>

namespace deepcheck::robots {

using detail::inQuotes;

namespace fs = std::filesystem;

const char* toString(JointType type) {
  switch (type) {
    case JointType::Fixed:
      return "fixed";
    case JointType::Revolute:
      return "revolute";
    case JointType::Continuous:
      return "continuous";
    case JointType::Prismatic:
      return "prismatic";
  }
  return "?";
}

const char* toString(GeometryType type) {
  switch (type) {
    case GeometryType::Box:
      return "box";
    case GeometryType::Sphere:
      return "sphere";
    case GeometryType::Cylinder:
      return "cylinder";
    case GeometryType::Mesh:
      return "mesh";
  }
  return "?";
}

namespace {

/// Collects what urdfdom reports through console_bridge while it parses, instead of printing it.
class CaptureHandler : public console_bridge::OutputHandler {
 public:
  void log(const std::string& text, console_bridge::LogLevel level, const char*, int) override {
    if (level >= console_bridge::CONSOLE_BRIDGE_LOG_ERROR) errors.push_back(text);
  }
  std::vector<std::string> errors;
};

/// urdf::parseURDF with its error messages captured. console_bridge's handler is global, so
/// concurrent loads take turns.
urdf::ModelInterfaceSharedPtr parseWithUrdfdom(const std::string& xml, std::string& errors) {
  static std::mutex mutex;
  std::lock_guard<std::mutex> lock(mutex);
  CaptureHandler handler;
  console_bridge::useOutputHandler(&handler);
  urdf::ModelInterfaceSharedPtr model;
  try {
    model = urdf::parseURDF(xml);
  } catch (const std::exception& e) {
    handler.errors.push_back(e.what());
    model.reset();
  }
  console_bridge::restorePreviousOutputHandler();
  for (const std::string& e : handler.errors) errors += (errors.empty() ? "" : "; ") + e;
  return model;
}

std::string format(const Eigen::Vector3d& v) {
  std::ostringstream s;
  s << v.x() << " " << v.y() << " " << v.z();
  return s.str();
}

Eigen::Isometry3d toIsometry(const urdf::Pose& pose) {
  Eigen::Quaterniond q(pose.rotation.w, pose.rotation.x, pose.rotation.y, pose.rotation.z);
  q.normalize();
  Eigen::Isometry3d X = Eigen::Isometry3d::Identity();
  X.linear() = q.toRotationMatrix();
  X.translation() = Eigen::Vector3d(pose.position.x, pose.position.y, pose.position.z);
  return X;
}

}  // namespace

/// Turns urdfdom's model into a RobotModel (see the header for the numbering).
class UrdfBuilder {
 public:
  UrdfBuilder(RobotModel& model, const urdf::ModelInterface& urdf, const std::map<std::string, int>& jointOrder,
              const std::string& context, const std::string& baseDirectory, const LoadOptions& options)
      : model_(model),
        urdf_(urdf),
        jointOrder_(jointOrder),
        context_(context),
        baseDirectory_(baseDirectory),
        options_(options),
        roots_(packageRoots(options.packageRoots, options.useRosPackagePath)) {}

  void build() {
    model_.name_ = urdf_.getName();
    const urdf::LinkConstSharedPtr root = urdf_.getRoot();
    if (!root) throw std::invalid_argument(context_ + ": no root link");
    addTree(*root);
    resolveMimics();
    collectVariables();
  }

 private:
  /// Numbers the links and joints depth first from the root (see the header). The walk keeps its
  /// own stack, as a chain of links may be as long as LoadOptions::maxLinks allows.
  void addTree(const urdf::Link& root) {
    std::vector<std::pair<urdf::JointSharedPtr, int>> pending;  // (joint, its parent link's index)
    pushChildren(root, addLink(root, -1), pending);
    while (!pending.empty()) {
      const auto [j, parentLink] = pending.back();
      pending.pop_back();
      const int jointIndex = addJoint(*j, parentLink);
      model_.links_[parentLink].childJoints.push_back(jointIndex);
      const urdf::LinkConstSharedPtr child = urdf_.getLink(j->child_link_name);
      if (!child) {
        throw std::invalid_argument(context_ + ": joint " + inQuotes(j->name) + " has unknown child link " +
                                    inQuotes(j->child_link_name));
      }
      pushChildren(*child, addLink(*child, jointIndex), pending);
    }
  }

  /// Adds the link (without its child joints) and returns its index.
  int addLink(const urdf::Link& link, int parentJoint) {
    const int index = static_cast<int>(model_.links_.size());
    model_.links_.emplace_back();
    Link& L = model_.links_.back();
    L.name = link.name;
    L.parentJoint = parentJoint;
    L.parentLink = parentJoint < 0 ? -1 : model_.joints_[parentJoint].parentLink;
    if (parentJoint >= 0) model_.joints_[parentJoint].childLink = index;
    addCollisions(link, index);
    return index;
  }

  /// Queues the child joints of `link` (index `index`) so that they are taken in file order
  /// (urdfdom keeps them sorted by name).
  void pushChildren(const urdf::Link& link, int index,
                    std::vector<std::pair<urdf::JointSharedPtr, int>>& pending) const {
    std::vector<urdf::JointSharedPtr> children = link.child_joints;
    std::sort(children.begin(), children.end(), [this](const auto& a, const auto& b) {
      return order(a->name) > order(b->name);  // reversed: the stack pops the first one first
    });
    for (const auto& j : children) pending.emplace_back(j, index);
  }

  int order(const std::string& jointName) const {
    auto it = jointOrder_.find(jointName);
    return it == jointOrder_.end() ? 0 : it->second;
  }

  void addCollisions(const urdf::Link& link, int index) {
    int c = 0;
    for (const urdf::CollisionSharedPtr& collision : link.collision_array) {
      const std::string where = context_ + ", link " + inQuotes(link.name) + ", collision " + std::to_string(c);
      ++c;
      if (!collision || !collision->geometry) {
        throw std::invalid_argument(where + ": no geometry");
      }
      CollisionElement element;
      element.name = collision->name;
      element.X_LG = toIsometry(collision->origin);
      Geometry& g = element.geometry;
      const urdf::Geometry& geometry = *collision->geometry;
      switch (geometry.type) {
        case urdf::Geometry::BOX: {
          const auto& box = static_cast<const urdf::Box&>(geometry);
          g.type = GeometryType::Box;
          g.boxSize = Eigen::Vector3d(box.dim.x, box.dim.y, box.dim.z);
          if (!(g.boxSize.array() > 0.0).all()) {
            std::ostringstream msg;
            msg << where << ": box size (" << format(g.boxSize) << ") must be positive";
            throw std::invalid_argument(msg.str());
          }
          break;
        }
        case urdf::Geometry::SPHERE: {
          g.type = GeometryType::Sphere;
          g.radius = static_cast<const urdf::Sphere&>(geometry).radius;
          if (!(g.radius > 0.0)) {
            throw std::invalid_argument(where + ": sphere radius " + formatNumber(g.radius) + " must be positive");
          }
          break;
        }
        case urdf::Geometry::CYLINDER: {
          const auto& cylinder = static_cast<const urdf::Cylinder&>(geometry);
          g.type = GeometryType::Cylinder;
          g.radius = cylinder.radius;
          g.length = cylinder.length;
          if (!(g.radius > 0.0) || !(g.length > 0.0)) {
            throw std::invalid_argument(where + ": cylinder radius " + formatNumber(g.radius) + " and length " +
                                        formatNumber(g.length) + " must be positive");
          }
          break;
        }
        case urdf::Geometry::MESH: {
          const auto& mesh = static_cast<const urdf::Mesh&>(geometry);
          g.type = GeometryType::Mesh;
          g.meshUri = mesh.filename;
          g.meshScale = Eigen::Vector3d(mesh.scale.x, mesh.scale.y, mesh.scale.z);
          if ((g.meshScale.array() == 0.0).any()) {
            std::ostringstream msg;
            msg << where << ": mesh scale (" << format(g.meshScale) << ") has a zero component";
            throw std::invalid_argument(msg.str());
          }
          g.meshPath = resolveUriOrThrow(mesh.filename, roots_, baseDirectory_, where);
          break;
        }
      }
      model_.links_[index].collisions.push_back(std::move(element));
    }
  }

  int addJoint(const urdf::Joint& j, int parentLink) {
    const std::string where = context_ + ", joint " + inQuotes(j.name);
    Joint joint;
    joint.name = j.name;
    joint.parentLink = parentLink;
    joint.X_PJ = toIsometry(j.parent_to_joint_origin_transform);
    switch (j.type) {
      case urdf::Joint::FIXED:
        joint.type = JointType::Fixed;
        joint.urdfType = "fixed";
        break;
      case urdf::Joint::REVOLUTE:
        joint.type = JointType::Revolute;
        joint.urdfType = "revolute";
        break;
      case urdf::Joint::CONTINUOUS:
        joint.type = JointType::Continuous;
        joint.urdfType = "continuous";
        break;
      case urdf::Joint::PRISMATIC:
        joint.type = JointType::Prismatic;
        joint.urdfType = "prismatic";
        break;
      case urdf::Joint::FLOATING:
      case urdf::Joint::PLANAR: {
        joint.urdfType = j.type == urdf::Joint::FLOATING ? "floating" : "planar";
        if (!options_.fixFloatingJoints) {
          throw std::invalid_argument(where + " is " + joint.urdfType +
                                      ", which is not supported; set LoadOptions::fixFloatingJoints "
                                      "to treat it as fixed at its origin");
        }
        joint.type = JointType::Fixed;
        break;
      }
      default:
        throw std::invalid_argument(where + " has an unknown type");
    }
    if (joint.moves()) {
      const Eigen::Vector3d axis(j.axis.x, j.axis.y, j.axis.z);
      if (!(axis.norm() >= tol::kMinAxisNorm)) {
        std::ostringstream msg;
        msg << where << ": axis (" << format(axis) << ") is zero";
        throw std::invalid_argument(msg.str());
      }
      joint.axis = axis.normalized();
      if (j.limits) joint.velocityLimit = j.limits->velocity;
      if (joint.type == JointType::Continuous) {
        joint.lower = -M_PI;
        joint.upper = M_PI;
      } else {
        if (!j.limits) throw std::invalid_argument(where + ": no <limit> for a " + joint.urdfType + " joint");
        joint.lower = j.limits->lower;
        joint.upper = j.limits->upper;
        if (joint.lower > joint.upper) {
          std::ostringstream msg;
          msg << where << ": lower limit " << joint.lower << " is above upper limit " << joint.upper;
          throw std::invalid_argument(msg.str());
        }
      }
      if (j.mimic) {
        mimics_.emplace_back(static_cast<int>(model_.joints_.size()), j.mimic->joint_name);
        joint.multiplier = j.mimic->multiplier;
        joint.offset = j.mimic->offset;
      }
    }
    model_.joints_.push_back(joint);
    return static_cast<int>(model_.joints_.size()) - 1;
  }

  void resolveMimics() {
    for (const auto& [index, target] : mimics_) {
      Joint& joint = model_.joints_[index];
      const int other = model_.jointIndex(target);
      if (other < 0) {
        throw std::invalid_argument(context_ + ", joint " + inQuotes(joint.name) + " mimics unknown joint " +
                                    inQuotes(target));
      }
      if (!model_.joints_[other].moves()) {
        throw std::invalid_argument(context_ + ", joint " + inQuotes(joint.name) + " mimics joint " + inQuotes(target) +
                                    ", which is fixed");
      }
      joint.mimicJoint = other;
    }
    // Follow each chain to its end: value = m1 * (m2 * (... q + b_k) + b2) + b1. The direct
    // multipliers and offsets are read from a copy, as the joints are updated in place.
    const std::vector<Joint> direct = model_.joints_;
    for (int j = 0; j < model_.numJoints(); ++j) {
      Joint& joint = model_.joints_[j];
      if (!joint.isMimic()) continue;
      double multiplier = direct[j].multiplier;
      double offset = direct[j].offset;
      std::vector<int> chain{j};
      int current = joint.mimicJoint;
      while (direct[current].isMimic()) {
        if (std::find(chain.begin(), chain.end(), current) != chain.end()) {
          std::string cycle;
          for (int c : chain) cycle += inQuotes(direct[c].name) + " -> ";
          cycle += inQuotes(direct[current].name);
          throw std::invalid_argument(context_ + ": mimic joints form a cycle: " + cycle);
        }
        chain.push_back(current);
        offset += multiplier * direct[current].offset;
        multiplier *= direct[current].multiplier;
        current = direct[current].mimicJoint;
      }
      joint.multiplier = multiplier;
      joint.offset = offset;
      resolvedSource_.emplace_back(j, current);
    }
  }

  void collectVariables() {
    std::vector<double> lower, upper;
    for (int j = 0; j < model_.numJoints(); ++j) {
      Joint& joint = model_.joints_[j];
      if (!joint.moves() || joint.isMimic()) continue;
      joint.variable = model_.numVariables();
      joint.multiplier = 1.0;
      joint.offset = 0.0;
      model_.variableJoints_.push_back(j);
      model_.variableNames_.push_back(joint.name);
      lower.push_back(joint.lower);
      upper.push_back(joint.upper);
    }
    for (const auto& [mimic, source] : resolvedSource_) {
      model_.joints_[mimic].variable = model_.joints_[source].variable;
    }
    model_.lower_ = Eigen::Map<const Eigen::VectorXd>(lower.data(), lower.size());
    model_.upper_ = Eigen::Map<const Eigen::VectorXd>(upper.data(), upper.size());
  }

  RobotModel& model_;
  const urdf::ModelInterface& urdf_;
  const std::map<std::string, int>& jointOrder_;
  const std::string& context_;
  const std::string& baseDirectory_;
  const LoadOptions& options_;
  std::vector<std::string> roots_;
  std::vector<std::pair<int, std::string>> mimics_;  // (joint, the joint it names)
  std::vector<std::pair<int, int>> resolvedSource_;  // (mimic joint, joint at the chain's end)
};

RobotModel RobotModel::fromUrdfFile(const std::string& path, const LoadOptions& options) {
  std::error_code ec;
  if (!fs::is_regular_file(path, ec)) {
    throw std::invalid_argument("URDF " + inQuotes(path) +
                                (fs::exists(path, ec) ? " is not a regular file" : " does not exist"));
  }
  std::ifstream in(path, std::ios::binary);
  if (!in) throw std::invalid_argument("URDF " + inQuotes(path) + " cannot be opened for reading");
  std::stringstream buffer;
  buffer << in.rdbuf();
  const fs::path base = fs::absolute(fs::path(path), ec).parent_path();
  return fromUrdfString(buffer.str(), base.string(), options, path);
}

RobotModel RobotModel::fromUrdfString(const std::string& xml, const std::string& baseDirectory,
                                      const LoadOptions& options, const std::string& sourceName) {
  RobotModel model;
  model.source_ = sourceName.empty() ? "<string>" : sourceName;
  const std::string context = "URDF " + inQuotes(model.source_);

  std::map<std::string, int> jointOrder;
  std::set<std::string> visualLinks;
  const std::string cleaned = detail::prepareUrdf(xml, context, options.maxLinks, jointOrder, visualLinks);
  std::string errors;
  const urdf::ModelInterfaceSharedPtr urdf = parseWithUrdfdom(cleaned, errors);
  if (!urdf) {
    throw std::invalid_argument(context +
                                ": urdfdom rejected it: " + (errors.empty() ? std::string("(no message)") : errors));
  }
  UrdfBuilder(model, *urdf, jointOrder, context, baseDirectory, options).build();
  for (Link& link : model.links_) link.hasVisual = visualLinks.count(link.name) > 0;
  return model;
}

int RobotModel::linkIndex(const std::string& name) const {
  for (int i = 0; i < numLinks(); ++i) {
    if (links_[i].name == name) return i;
  }
  return -1;
}

int RobotModel::jointIndex(const std::string& name) const {
  for (int i = 0; i < numJoints(); ++i) {
    if (joints_[i].name == name) return i;
  }
  return -1;
}

int RobotModel::variableIndex(const std::string& name) const {
  for (int v = 0; v < numVariables(); ++v) {
    if (variableNames_[v] == name) return v;
  }
  return -1;
}

int RobotModel::numCollisionElements() const {
  int n = 0;
  for (const Link& l : links_) n += static_cast<int>(l.collisions.size());
  return n;
}

Eigen::VectorXd RobotModel::defaultConfiguration() const {
  return Eigen::VectorXd::Zero(numVariables()).cwiseMax(lower_).cwiseMin(upper_);
}

void RobotModel::setBasePose(const Eigen::Isometry3d& X_WR) {
  const Eigen::Matrix3d R = X_WR.linear();
  const double error = (R.transpose() * R - Eigen::Matrix3d::Identity()).cwiseAbs().maxCoeff();
  if (!X_WR.matrix().allFinite() || !(error <= tol::kOrthonormality) || R.determinant() < 0.0) {
    std::ostringstream msg;
    msg << "robot " << inQuotes(name_) << ": base pose is not a finite rigid transform:\n" << X_WR.matrix();
    throw std::invalid_argument(msg.str());
  }
  X_WR_ = X_WR;
}

}  // namespace deepcheck::robots
