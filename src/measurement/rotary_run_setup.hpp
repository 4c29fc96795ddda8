#pragma once
// What the rotary-axis tests and a measurement design's candidate runs share: the pose they start
// from, a direction across an axis line, and the test plan's text for a point and a pose. Private
// to the measurement module.
#include <string>
#include <vector>

#include "mtacc/core/transform.hpp"
#include "mtacc/machine/machine.hpp"

namespace mtacc {

// The linear axes at the middle of their travels, the rotary axes at zero (or at the middle of a
// travel without it); commanded axes.
std::vector<double> startPose(const Machine& m);

// A unit vector across a line of the given direction: the machine axis most across it, made square to it.
Vec3 across(const Vec3& direction);

// "[x mm, y mm, z mm]", as a test plan writes a point.
std::string mm(const Vec3& v);

// ", pose: {B: -30 deg}": the rotary axes other than `moving` (-1: every one) at q, as a test
// plan's run gives them; "" on a machine with no other rotary axis.
std::string poseEntry(const Machine& m, const std::vector<double>& q, int moving);

}  // namespace mtacc
