#include "scene_yaml.h"

#include "deepcheck/robots/moveit_scene.h"

#include <deepcheck/geometry/input_range.h>

#include <yaml-cpp/eventhandler.h>

#include <cmath>
#include <sstream>
#include <stdexcept>

namespace deepcheck::robots::scene_yaml {

std::string Context::where(const YAML::Node& node) const {
  std::string out = "planning scene '" + source + "'";
  const int line = lineOf(node);
  if (line > 0) out += ", line " + std::to_string(line);
  if (!object.empty()) out += ", " + object;
  return out;
}

void Context::fail(const YAML::Node& node, const std::string& what) const {
  throw std::invalid_argument(where(node) + ": " + what);
}

namespace {

/// Follows the nesting of maps and sequences, throwing when it passes kMaxNestingDepth. yaml-cpp
/// calls OnMapStart and OnSequenceStart before it reads (recursively) what they hold.
class DepthCheck : public YAML::EventHandler {
 public:
  explicit DepthCheck(const std::string& source) : source_(source) {}
  void OnDocumentStart(const YAML::Mark&) override {}
  void OnDocumentEnd() override {}
  void OnNull(const YAML::Mark&, YAML::anchor_t) override {}
  void OnAlias(const YAML::Mark&, YAML::anchor_t) override {}
  void OnScalar(const YAML::Mark&, const std::string&, YAML::anchor_t, const std::string&) override {}
  void OnSequenceStart(const YAML::Mark& mark, const std::string&, YAML::anchor_t, YAML::EmitterStyle::value) override {
    enter(mark);
  }
  void OnSequenceEnd() override { --depth_; }
  void OnMapStart(const YAML::Mark& mark, const std::string&, YAML::anchor_t, YAML::EmitterStyle::value) override {
    enter(mark);
  }
  void OnMapEnd() override { --depth_; }

 private:
  void enter(const YAML::Mark& mark) {
    if (++depth_ <= kMaxNestingDepth) return;
    throw std::invalid_argument("planning scene '" + source_ + "', line " + std::to_string(mark.line + 1) +
                                ": collections nested " + std::to_string(depth_) +
                                " levels deep, more than the limit of " + std::to_string(kMaxNestingDepth));
  }

  const std::string& source_;
  int depth_ = 0;
};

}  // namespace

YAML::Node loadYaml(const std::string& text, const std::string& source) {
  std::istringstream stream(text);
  YAML::Parser parser(stream);
  DepthCheck check(source);
  parser.HandleNextDocument(check);
  return YAML::Load(text);
}

int lineOf(const YAML::Node& node) {
  if (!node.IsDefined()) return 0;  // also false for a missing key (an invalid node)
  const YAML::Mark mark = node.Mark();
  return mark.is_null() ? 0 : mark.line + 1;
}

YAML::Node required(const Context& ctx, const YAML::Node& parent, const char* key) {
  if (!parent.IsMap()) ctx.fail(parent, std::string("expected a map with '") + key + "'");
  YAML::Node child = parent[key];
  if (!child.IsDefined()) ctx.fail(parent, std::string("missing '") + key + "'");
  if (child.IsNull()) ctx.fail(child, std::string("'") + key + "' is empty");
  return child;
}

void checkKeys(const Context& ctx, const YAML::Node& node, const char* what,
               std::initializer_list<const char*> allowed) {
  if (!node.IsMap()) ctx.fail(node, std::string(what) + " must be a map");
  for (const auto& entry : node) {
    if (!entry.first.IsScalar()) ctx.fail(entry.first, std::string(what) + " has a key that is not a name");
    const std::string& key = entry.first.Scalar();
    bool known = false;
    for (const char* a : allowed) known = known || key == a;
    if (known) continue;
    std::string list;
    for (const char* a : allowed) list += (list.empty() ? "" : ", ") + std::string(a);
    ctx.fail(entry.first, "unknown key '" + key + "' in " + what + " (known: " + list + ")");
  }
  // yaml-cpp keeps repeated keys; refusing them bounds the work on a map repeated by aliases.
  // (Checked after the names, so that an unknown key is reported as such.)
  if (node.size() > allowed.size()) ctx.fail(node, std::string(what) + " has repeated keys");
}

std::string readString(const Context& ctx, const YAML::Node& node, const std::string& what) {
  if (!node.IsScalar()) ctx.fail(node, what + " must be a single value");
  return node.Scalar();
}

bool readBool(const Context& ctx, const YAML::Node& node, const std::string& what) {
  bool value = false;
  if (!node.IsScalar() || !YAML::convert<bool>::decode(node, value)) {
    ctx.fail(node, what + " must be true or false" + (node.IsScalar() ? ", is '" + node.Scalar() + "'" : ""));
  }
  return value;
}

double readNumber(const Context& ctx, const YAML::Node& node, const std::string& what) {
  if (!node.IsScalar()) ctx.fail(node, what + " must be a number");
  double value = 0.0;
  if (!YAML::convert<double>::decode(node, value)) {
    ctx.fail(node, what + " must be a number, is '" + node.Scalar() + "'");
  }
  if (!std::isfinite(value)) ctx.fail(node, what + " must be finite, is '" + node.Scalar() + "'");
  if (std::abs(value) > geometry::range::kMaxCoordinate) {
    std::ostringstream msg;
    msg << what << " must have magnitude at most " << geometry::range::kMaxCoordinate << ", is '" << node.Scalar()
        << "'";
    ctx.fail(node, msg.str());
  }
  return value;
}

std::vector<double> readNumbers(const Context& ctx, const YAML::Node& node, const std::string& what) {
  if (!node.IsSequence()) ctx.fail(node, what + " must be a list of numbers");
  std::vector<double> out;
  for (size_t i = 0; i < node.size(); ++i) {
    out.push_back(readNumber(ctx, node[i], what + "[" + std::to_string(i) + "]"));
  }
  return out;
}

namespace {

/// The components of a vector or quaternion: a list of `names.size()` numbers or a map with
/// exactly those keys.
std::vector<double> readComponents(const Context& ctx, const YAML::Node& node, const std::string& what,
                                   const std::vector<const char*>& names) {
  std::vector<double> out;
  if ((node.IsMap() || node.IsSequence()) && node.size() != names.size()) {
    ctx.fail(node,
             what + " must have " + std::to_string(names.size()) + " numbers, has " + std::to_string(node.size()));
  }
  if (node.IsMap()) {
    for (const auto& entry : node) {
      const std::string key = entry.first.IsScalar() ? entry.first.Scalar() : "";
      bool known = false;
      for (const char* n : names) known = known || key == n;
      if (!known) ctx.fail(entry.first, what + " has an unknown component '" + key + "'");
    }
    for (const char* n : names) out.push_back(readNumber(ctx, required(ctx, node, n), what + "." + n));
    return out;
  }
  if (!node.IsSequence()) ctx.fail(node, what + " must be a list or a map");
  return readNumbers(ctx, node, what);
}

}  // namespace

Eigen::Vector3d readVector3(const Context& ctx, const YAML::Node& node, const std::string& what) {
  const std::vector<double> v = readComponents(ctx, node, what, {"x", "y", "z"});
  return Eigen::Vector3d(v[0], v[1], v[2]);
}

Eigen::Quaterniond readQuaternion(const Context& ctx, const YAML::Node& node, const std::string& what) {
  const std::vector<double> v = readComponents(ctx, node, what, {"x", "y", "z", "w"});
  Eigen::Quaterniond q(v[3], v[0], v[1], v[2]);  // Eigen's constructor takes w first
  const double norm = q.norm();
  if (!(std::abs(norm - 1.0) <= tol::kSceneQuaternionNorm)) {
    std::ostringstream msg;
    msg << what << " [x y z w] = [" << v[0] << ", " << v[1] << ", " << v[2] << ", " << v[3] << "] has norm " << norm
        << ", not 1 (within " << tol::kSceneQuaternionNorm << ")";
    ctx.fail(node, msg.str());
  }
  q.normalize();
  return q;
}

namespace {

/// A rigid transform written as a translation and a quaternion under the given keys.
Eigen::Isometry3d readRigid(const Context& ctx, const YAML::Node& node, const std::string& what,
                            const char* translationKey, const char* rotationKey) {
  checkKeys(ctx, node, what.c_str(), {translationKey, rotationKey});
  Eigen::Isometry3d X = Eigen::Isometry3d::Identity();
  X.translation() = readVector3(ctx, required(ctx, node, translationKey), what + "." + translationKey);
  X.linear() = readQuaternion(ctx, required(ctx, node, rotationKey), what + "." + rotationKey).toRotationMatrix();
  return X;
}

}  // namespace

Eigen::Isometry3d readPose(const Context& ctx, const YAML::Node& node, const std::string& what) {
  return readRigid(ctx, node, what, "position", "orientation");
}

Eigen::Isometry3d readTransform(const Context& ctx, const YAML::Node& node, const std::string& what) {
  return readRigid(ctx, node, what, "translation", "rotation");
}

}  // namespace deepcheck::robots::scene_yaml
