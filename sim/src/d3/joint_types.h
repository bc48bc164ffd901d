// SPDX-License-Identifier: MIT
#pragma once
// The functions of each joint type, one file each (joint_<type>.cpp),
// gathered into joint_ops()'s table in joint_solver.cpp.
#include "d3/joint_solver.h"

namespace rwd::sim::d3 {

extern const JointOps kBallOps;       // joint_ball.cpp
extern const JointOps kHingeOps;      // joint_hinge.cpp
extern const JointOps kWeldOps;       // joint_weld.cpp
extern const JointOps kDistanceOps;   // joint_distance.cpp (distance and spring)
extern const JointOps kPrismaticOps;  // joint_prismatic.cpp
extern const JointOps kGrabOps;       // joint_grab.cpp

}  // namespace rwd::sim::d3
