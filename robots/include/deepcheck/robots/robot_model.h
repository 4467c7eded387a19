#pragma once
// A robot (or a scene: a URDF too) as the collision checker needs it: a tree of links with their
// COLLISION geometry, joints, and the configuration vector that moves them.
//
// Loading. The URDF is read with TinyXML first (malformed XML is reported with its line and
// column; every number of an <origin>, <axis>, <limit>, <mimic> and of the collision geometry is
// checked to be finite; <visual> and <inertial> blocks are dropped unread, so a broken or missing
// visual mesh never matters; only whether a link has a <visual> is kept, Link::hasVisual), then
// handed to urdfdom. Only <collision> elements are used; a link
// may have several. Mesh URIs are resolved at load time (package_path.h); the meshes themselves
// are read later, by collision_geometry.h.
//
// Frames (Drake notation: X_AB is the pose of frame B in frame A, p_AQ the position of point Q in
// A). W is the world, L a link's frame, P a joint's parent link, C its child link, J the joint
// frame (URDF <joint><origin>), G a collision element's frame (URDF <collision><origin>).
//   X_WR   pose of the root link R in the world: basePose(), settable; a scene is placed this way.
//   X_PJ   Joint::X_PJ, constant.
//   X_JC   the joint's motion: a rotation of `value` radians about `axis` (right-handed) for
//          revolute and continuous joints, a translation of `value` metres along `axis` for
//          prismatic ones, the identity for fixed ones. At value 0, C coincides with J.
//   X_LG   CollisionElement::X_LG, constant.
// Units: metres, radians.
//
// Order. Links are numbered depth-first from the root (index 0), a link's children in the order
// their joints appear in the URDF file; so a parent always precedes its children. Joints are
// numbered in the same order: joint i is the parent joint of link i + 1. The configuration q
// holds one value per VARIABLE: the revolute, continuous and prismatic joints that are not
// mimic joints, in joint order. variableNames() lists them; variableIndex("panda_joint1") finds one.
//
// Joint values. Every moving joint's value is multiplier * q[variable] + offset: an ordinary joint
// has multiplier 1 and offset 0; a mimic joint (<mimic joint="o" multiplier="m" offset="b"/>,
// value = m * value(o) + b) gets the composed multiplier and offset of its chain, so a mimic of a
// mimic is resolved to the variable at the end of the chain. A cycle of mimic joints is an error.
//
// Limits. lowerLimits()/upperLimits() are the URDF limits of the variables. Continuous joints
// have none in the URDF; they are given [-pi, pi], which reaches every orientation and keeps the
// bounds finite for samplers. Planners wrap them around instead (joint_angles.h: which variables
// wrap, and their values normalized to (-pi, pi]). Forward kinematics accepts any finite value;
// limits are not enforced there.
//
// Locked joints. withLockedVariables() gives a copy of the model in which chosen variables are
// held at given values, as a planning group holds the joints outside it: each of their joints
// (mimic joints included) becomes a fixed joint whose X_PJ includes its motion at that value
// (Joint::locked, Joint::lockedValue keep what it was), and the remaining variables are
// renumbered in joint order. Everything built on the copy (kinematics, Jacobians, IK, the
// checker, state spaces) then sees only the remaining variables.
//
// Floating and planar joints are rejected (the message names the joint) unless
// LoadOptions::fixFloatingJoints, in which case they become fixed joints at their origin
// (Joint::urdfType keeps the word written in the file).
//
// Limits. Elements nested deeper than kMaxNestingDepth are rejected before TinyXML reads the
// text; a URDF with more than LoadOptions::maxLinks links (or joints) before urdfdom reads it;
// every number read must be finite with magnitude at most geometry::range::kMaxCoordinate (1e50, the
// range the distance queries support), so that a pose far out is rejected here, naming the link
// or joint, and not by a query later.
//
// Errors: every problem throws std::invalid_argument whose message starts with
// "URDF '<file>'" and names the link, joint or value at fault.

#include <Eigen/Core>
#include <Eigen/Geometry>

#include <map>
#include <string>
#include <vector>

namespace deepcheck::robots {

/// Deepest nesting accepted in a file read by this library, in levels: XML elements (URDF, SRDF,
/// COLLADA and the other XML mesh formats; the root element is level 1) and YAML collections
/// (planning scenes). The parsers recurse once per level, so deeper files would overflow the
/// stack; they are rejected before being parsed. Real files stay within a few tens of levels.
constexpr int kMaxNestingDepth = 256;

enum class JointType {
  Fixed,       ///< no motion
  Revolute,    ///< rotation about the axis, limited
  Continuous,  ///< rotation about the axis, unlimited (limits reported as [-pi, pi])
  Prismatic,   ///< translation along the axis
};
const char* toString(JointType type);

enum class GeometryType { Box, Sphere, Cylinder, Mesh };
const char* toString(GeometryType type);

/// One URDF collision geometry, in its own frame G.
struct Geometry {
  GeometryType type = GeometryType::Box;
  Eigen::Vector3d boxSize = Eigen::Vector3d::Zero();    ///< Box: full edge lengths along x, y, z of G
  double radius = 0.0;                                  ///< Sphere and Cylinder
  double length = 0.0;                                  ///< Cylinder: along z of G, centred on G's origin
  std::string meshUri;                                  ///< Mesh: the filename as written in the URDF
  std::string meshPath;                                 ///< Mesh: the resolved absolute path
  Eigen::Vector3d meshScale = Eigen::Vector3d::Ones();  ///< Mesh: URDF scale
};

/// One <collision> element of a link.
struct CollisionElement {
  std::string name;                                        ///< the URDF name attribute ("" when absent)
  Eigen::Isometry3d X_LG = Eigen::Isometry3d::Identity();  ///< pose of G in the link frame
  Geometry geometry;
};

struct Link {
  std::string name;
  int parentJoint = -1;          ///< joint whose child this link is (-1 for the root)
  int parentLink = -1;           ///< (-1 for the root)
  std::vector<int> childJoints;  ///< in URDF order
  std::vector<CollisionElement> collisions;
  /// The URDF link has a <visual> element (its contents are not read). A link with a visual but
  /// no collision element is invisible to the checker, which callers may want to say.
  bool hasVisual = false;
};

struct Joint {
  std::string name;
  JointType type = JointType::Fixed;
  std::string urdfType;  ///< the type as written in the URDF ("floating" for a fixed-up one)
  int parentLink = -1;
  int childLink = -1;
  Eigen::Isometry3d X_PJ = Eigen::Isometry3d::Identity();  ///< joint frame in the parent link
  Eigen::Vector3d axis = Eigen::Vector3d::UnitX();         ///< unit, in J (= in C); moving joints only
  double lower = 0.0;  ///< position limits, rad or m (continuous: -pi, pi; fixed: 0, 0)
  double upper = 0.0;
  double velocityLimit = 0.0;  ///< rad/s or m/s (0 when the URDF gives none)
  /// value = multiplier * q[variable] + offset; variable is -1 for fixed joints.
  int variable = -1;
  double multiplier = 1.0;
  double offset = 0.0;
  int mimicJoint = -1;  ///< the joint this one mimics directly (-1 when not a mimic)
  /// A moving URDF joint held fixed by RobotModel::withLockedVariables (type is Fixed, X_PJ
  /// includes its motion at lockedValue, rad or m).
  bool locked = false;
  double lockedValue = 0.0;
  bool isMimic() const { return mimicJoint >= 0; }
  bool moves() const { return type != JointType::Fixed; }
};

struct LoadOptions {
  /// Package roots searched first for package:// URIs (the deepcheck tool fills it from its
  /// --package-path options).
  std::vector<std::string> packageRoots;
  /// Also search ROS_PACKAGE_PATH (and AMENT_PREFIX_PATH/share).
  bool useRosPackagePath = true;
  /// Treat floating and planar joints as fixed at their origin instead of rejecting them.
  bool fixFloatingJoints = false;
  /// Most <link> elements, and most <joint> elements, a URDF may hold (real robots hold a few
  /// hundred at most); more is an error naming the file and the count, raised before the rest of
  /// the file is checked.
  int maxLinks = 10000;
};

class RobotModel {
 public:
  /// Loads a URDF file; relative mesh paths are relative to its folder.
  static RobotModel fromUrdfFile(const std::string& path, const LoadOptions& options = {});
  /// Loads URDF text; relative mesh paths are relative to `baseDirectory`. `sourceName` names
  /// the text in messages ("<string>" when empty).
  static RobotModel fromUrdfString(const std::string& xml, const std::string& baseDirectory,
                                   const LoadOptions& options = {}, const std::string& sourceName = "");

  const std::string& name() const { return name_; }      ///< the <robot name>
  const std::string& source() const { return source_; }  ///< file path or sourceName

  int numLinks() const { return static_cast<int>(links_.size()); }
  const std::vector<Link>& links() const { return links_; }
  const Link& link(int i) const { return links_.at(i); }
  /// Index of the link called `name`, -1 when there is none.
  int linkIndex(const std::string& name) const;

  int numJoints() const { return static_cast<int>(joints_.size()); }
  const std::vector<Joint>& joints() const { return joints_; }
  const Joint& joint(int i) const { return joints_.at(i); }
  /// Index of the joint called `name`, -1 when there is none.
  int jointIndex(const std::string& name) const;

  /// Total number of <collision> elements over all links.
  int numCollisionElements() const;

  int numVariables() const { return static_cast<int>(variableJoints_.size()); }
  const std::vector<std::string>& variableNames() const { return variableNames_; }
  /// Position of joint `name` in q; -1 when no such joint or it is fixed or a mimic joint.
  int variableIndex(const std::string& name) const;
  /// The joint driven by variable v.
  int variableJoint(int v) const { return variableJoints_.at(v); }
  const Eigen::VectorXd& lowerLimits() const { return lower_; }
  const Eigen::VectorXd& upperLimits() const { return upper_; }
  /// Zero clamped into the limits: a configuration that is always within them.
  Eigen::VectorXd defaultConfiguration() const;

  /// A copy with the variables named in `values` (variable name -> rad or m) held at those
  /// values (header comment). Throws std::invalid_argument naming the robot, the name and the
  /// value for a name that is not a variable (a mimic or fixed joint: the message says which),
  /// a non-finite value, or a value outside the variable's limits.
  RobotModel withLockedVariables(const std::map<std::string, double>& values) const;

  /// X_WR, the pose of the root link in the world (identity unless set).
  const Eigen::Isometry3d& basePose() const { return X_WR_; }
  /// Places the robot (or scene). Throws std::invalid_argument unless X_WR is finite with an
  /// orthonormal, right-handed rotation (tol::kOrthonormality).
  void setBasePose(const Eigen::Isometry3d& X_WR);

 private:
  RobotModel() = default;
  friend class UrdfBuilder;

  std::string name_;
  std::string source_;
  std::vector<Link> links_;
  std::vector<Joint> joints_;
  std::vector<int> variableJoints_;
  std::vector<std::string> variableNames_;
  Eigen::VectorXd lower_;
  Eigen::VectorXd upper_;
  Eigen::Isometry3d X_WR_ = Eigen::Isometry3d::Identity();
};

/// `model` with every variable except those in `keep` (variable indices, e.g. a planning group's)
/// locked: at its value in `values` (variable name -> rad or m) when given, else at its default
/// (zero clamped into its limits). `keepName` names the kept set in messages ("group
/// 'panda_arm'"). Throws std::invalid_argument for a kept variable named in `values` (it would
/// be both planned and held), an index out of range, and what withLockedVariables throws.
RobotModel lockAllBut(const RobotModel& model, const std::vector<int>& keep,
                      const std::map<std::string, double>& values, const std::string& keepName);

}  // namespace deepcheck::robots
