#pragma once
// All numerical tolerances and defaults of deepcheck::planners, in one place.
//
// Lengths are metres (workspace) or radians (joint space, for revolute joints; metres for
// prismatic ones). "Joint-space length" is the state space's distance: for makeStateSpace's
// RealVectorStateSpace the Euclidean norm of the difference of two configurations; with continuous
// joints (SO2 components, state_space.h) the sum of the components' distances.

namespace deepcheck::planners::tol {

/// Longest motion segment that the discrete checks (OMPL's DiscreteMotionValidator, our motion
/// validator's fallback steps, objective integration) leave unchecked, as a fraction of the state
/// space's maximum extent. MoveIt's default (longest_valid_segment_fraction 0.005); on the bundled
/// 7-DOF arm (extent ~13.8 rad) it is ~0.069 rad.
constexpr double kDefaultSegmentFraction = 0.005;

/// The clearance motion validator's smallest step, as a fraction of the longest valid segment: a
/// certified step shorter than this is replaced by this uncertified one (the discrete fallback).
/// Smaller values certify closer to obstacles at the cost of more queries there; 1 would make the
/// fallback exactly the discrete pass's resolution.
constexpr double kFallbackStepFraction = 0.25;

/// ... and no point of the robot moves more than this (metres, by the link speed bound) in one
/// fallback step: a discrete step in joint space can carry a fingertip through a 4 cm wall, this
/// cannot carry anything through more than 0.5 mm of obstacle.
constexpr double kFallbackDisplacement = 0.0005;

/// makePlanner's range for planners that do not optimize (RRTConnect, RRT, ...), as a fraction of
/// the state space's maximum extent: 1.5 rad on the Panda's arm, 1.6 rad on the bundled arm,
/// 3.5 rad on a UR5 with joints of +-2 pi (OMPL's own default is 0.2 of the extent). With
/// certified motions a long motion far from obstacles is proven by a few tests, and fewer, longer
/// edges leave less to simplify: on the Panda in MotionBenchMaker's scenes (8 x 100 problems,
/// RRTConnect), 0.115 against 0.075 took the median plan + simplify from 3.39 to 2.92 ms and the
/// mean plan from 39 to 17 ms, for simplified paths 4 % longer (bench/README.md, "MotionBenchMaker
/// benchmark").
constexpr double kDefaultRangeFraction = 0.115;

/// Distance queries that only need to know whether sd exceeds a threshold t ask for distances up
/// to max(t, 0) + this (metres): a cap strictly above both t and 0, so that pairs whose bounding
/// volumes touch are always measured. Far below any geometric feature.
constexpr double kDistanceCapMargin = 1e-6;

/// Push-out aims at this much signed distance ABOVE the acceptance threshold (metres), so that
/// the linearization error of the last step cannot leave the result invalid. Also the contact
/// margin: every pair nearer than threshold + this is kept away, not only the deepest one.
constexpr double kPushOutTargetClearance = 1e-3;

/// Damping of the damped-least-squares step (metres per radian: the units of a row of the
/// signed-distance gradient). Rows much shorter than this (a pair the joints barely move) get
/// small steps instead of huge ones.
constexpr double kPushOutDamping = 0.02;

/// Largest change of one joint value in one push-out iteration (rad or m): keeps the step where
/// the linearization is meaningful.
constexpr double kPushOutMaxJointStep = 0.1;

/// Pairs up to this far above the push-out target (metres) are watched: a step that would bring
/// one of them inside the target makes it a constraint too (active set), so that pushing one pair
/// out does not push another one in (a gripper straddling a wall).
constexpr double kPushOutLookahead = 0.02;

/// Bundle of the push-out (see push_out.h): the linearizations of a pair's distance made at
/// earlier iterates stay constraints while the iterate is within this distance of where they were
/// made (largest joint difference, rad or m); at most kPushOutBundleSize of them are kept, newest
/// first. A pair's analytic gradient is one of its one-sided derivatives where the witness jumps
/// (a flat face pressed onto an edge); the gradients from both sides, kept together, make the
/// step leave along a direction that helps on both.
constexpr double kPushOutBundleRadius = 0.2;
constexpr int kPushOutBundleSize = 16;

/// Pattern-search fallback of the push-out: when the minimum distance has not improved by
/// kPushOutStallImprovement (metres) over kPushOutStallIterations iterations, or the gradients
/// give no step, single joints are tried at +-each of kPushOutProbeSteps (rad or m, increasing).
/// Penetration depth is the SHORTEST separating translation; where the cheap way out in joint
/// space goes another way (an arm poking sideways into a table edge that tilting lets slip under
/// it), the gradient is flat and only a probe sees the exit.
constexpr double kPushOutStallImprovement = 1e-4;
constexpr int kPushOutStallIterations = 5;
constexpr double kPushOutProbeSteps[] = {0.05, 0.1, 0.2, 0.4};

/// Push-out iterations before giving up.
constexpr int kPushOutMaxIterations = 50;

/// Deepest penetration (metres) the push-out starts from: deeper configurations are not "slightly
/// colliding" and are left alone (PushOutStatus::TooDeep).
constexpr double kPushOutMaxDepth = 0.05;

/// Cap on the estimated cost of one body query of the push-out (PushOutOptions::bodyBuildCost,
/// geometry::BodyDepthOptions::maxBuildCost: microseconds of a current x86-64 core, estimated from
/// the pieces' sizes). A tool pressed into a few boxes costs tens; two links of the bundled arm,
/// pieces of up to 64 vertices, often more, and such a contact keeps its pairwise answer. Larger
/// caps repaired no more starts in push_out_body_bench and made a deep start's push-out several
/// times slower (much more under the sanitizers).
constexpr double kPushOutBodyBuildCost = 300.0;

/// Body queries one push-out search makes at most (each capped by kPushOutBodyBuildCost): past
/// them the body-depth search stops and the pairwise one runs from the start, so one push-out's
/// body work is bounded too. The hard cases converge in one or two; 20 bounds a deep start of the
/// bundled arm to tens of milliseconds and repairs as many starts as 100 (push_out_body_bench).
constexpr int kPushOutMaxBodyQueries = 20;

/// Path repair (path_tools.h) pushes states out to at least this clearance above the threshold
/// (metres), so that the chords between repaired neighbours clear the edges they wrap around.
constexpr double kRepairClearance = 0.005;

/// Endpoint repair (setup.h: repairStartAndGoal, `deepcheck plan --repair-start`) pushes an
/// invalid start or goal out to at least this clearance above the validity threshold (metres), not
/// just past contact: a start left micrometres from an obstacle makes the first motion of every
/// path graze it. The default of --repair-margin.
constexpr double kEndpointRepairMargin = 0.001;

/// Random-jiggle baseline (MoveIt's FixStartStateCollision): each attempt moves every joint
/// uniformly within +-fraction of its range; kJiggleAttempts attempts.
constexpr double kJiggleFraction = 0.05;
constexpr int kJiggleAttempts = 100;

/// Safe distance of the clearance hinge objective, metres: states nearer than this to an
/// obstacle pay max(0, d_safe - sd).
constexpr double kDefaultSafeDistance = 0.05;

/// Safe distance of the hinge for the robot's self pairs, metres: 0, so self pairs pay only for
/// penetration. An arm's wrist links stay a few centimetres apart in every configuration (link5
/// and link7 of the bundled arm: 1-4 cm), so a self clearance goal would tax every path alike.
constexpr double kDefaultSelfSafeDistance = 0.0;

/// Weight of the hinge objective against path length (1 / metre): with 100, a path that stays
/// 1 cm inside the safe distance along 0.1 rad of motion costs as much as 0.1 rad more length.
/// The planners suite asserts, with this weight, that RRT* paths of a planar arm passing a pole
/// keep more than 0.6 times the safe distance from it (tests/planners/test_objectives.cpp).
constexpr double kDefaultHingeWeight = 100.0;

/// RRT*'s range (its longest extension, which also caps its rewiring radius) for objectives whose
/// motion costs are expensive, as a fraction of the state space's maximum extent (planner_factory.h:
/// prepareForCostlyObjective). OMPL's default is 0.2: 5.76 rad on a UR5 (28.8 rad across), and
/// RRT*'s radius min(range, r(n)) stays at the range for the first ~10^4 nodes, so every new node
/// asks the clearance cost of the motion to most of the tree. 0.04 (1.15 rad on a UR5, 0.55 rad on
/// the bundled arm) measured 25,000 to 30,000 RRT* iterations in 8 s instead of 3,300 on a UR5
/// (docs/planners.md, "Optimizing planners and the clearance objective").
constexpr double kCostlyObjectiveRangeFraction = 0.04;

/// Entries of a validity checker's memo of certified motions (certified_motion_memo.h): an entry
/// holds one end of a certified motion (its point, its offset on the motion and the motion's
/// displacement). A planned path's motions, its simplification's and their checks again stay
/// within a few hundred; 4096 entries keep a long path's 2048 motions (4096 x 3 x 7 doubles,
/// 690 KB, for a 7-joint arm). A multiple of the memo's two ways.
constexpr int kCertifiedMotionMemoSlots = 4096;

/// Slots of a certified motion validator's memo of refused motions (refused_motion_memo.h): the
/// refusals a path simplification asks again come within a few dozen motions of the first (256 x
/// 3 x 7 doubles, 43 KB, for a 7-joint arm).
constexpr int kRefusedMotionMemoSlots = 256;

/// The memo answers a motion whose ends lie within this distance of a certified motion, per
/// joint value and relative to 1 + the largest magnitude of the point's values and of the
/// motion's displacement (radians or metres): about 45 ulps, the round-off of computing a point of
/// a segment (OMPL's interpolation, path subdivision), which the configurations q1 + t dq the
/// certification itself tests carry as well. A configuration that far off the motion moves a point
/// of the robot by at most this times its distance from the joint axes: about the narrow phase's
/// contact tolerance of a pair (geometry::tol::kContactRelative times its size).
constexpr double kCertifiedMotionMemoTube = 1e-14;

/// The most pieces after the first that the memo of certified motions joins into one straight
/// motion (certified_motion_memo.h); each joint lies within kCertifiedMotionMemoTube divided by
/// this of the joined motion, so the joined motion stays within the tube of its pieces. A longer
/// line is recorded as several joined motions.
constexpr int kCertifiedMotionMemoJoins = 32;

/// Attempts of simplifySolutionChecked (setup.h) before it keeps the path as planned.
constexpr int kSimplifyAttempts = 3;

/// Resolution of the ground-truth checks used by the path verification (path_tools.h) unless
/// given: joint-space length between two checked states (rad). At 1 m from the axis a point moves
/// at most ~2 mm between checks on the bundled arm.
constexpr double kFineResolution = 0.002;

/// Pose goals (pose_goal.h). The goal's sampling thread stops after kPoseGoalMaxStates distinct
/// collision-free IK solutions (a bidirectional planner grows one tree from each; more rarely
/// help), or after kPoseGoalMaxFailedSamples consecutive IK calls (each with all its restarts)
/// that found none: the pose is then taken as unreachable without collision.
constexpr int kPoseGoalMaxStates = 16;
constexpr int kPoseGoalMaxFailedSamples = 8;
/// Two IK solutions closer than this (joint-space length, rad) are the same goal state.
constexpr double kPoseGoalMinSeparation = 0.01;

}  // namespace deepcheck::planners::tol
