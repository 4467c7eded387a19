#pragma once
// deepcheck::robots in one include: URDF robots and scenes, MoveIt planning scenes, meshes,
// collision geometry (meshes made into pieces by deepcheck/decomposition.h), kinematics, inverse
// kinematics, random configurations, collision-pair filtering and SRDF files.

#include "deepcheck/robots/collision_geometry.h"
#include "deepcheck/robots/inverse_kinematics.h"
#include "deepcheck/robots/joint_angles.h"
#include "deepcheck/robots/kinematics.h"
#include "deepcheck/robots/mesh.h"
#include "deepcheck/robots/mesh_loader.h"
#include "deepcheck/robots/moveit_scene.h"
#include "deepcheck/robots/package_path.h"
#include "deepcheck/robots/pair_filter.h"
#include "deepcheck/robots/random_configuration.h"
#include "deepcheck/robots/robot_model.h"
#include "deepcheck/robots/srdf.h"
#include "deepcheck/robots/tolerances.h"
