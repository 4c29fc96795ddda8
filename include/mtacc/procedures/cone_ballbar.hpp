#pragma once
// Seed 000 ch. 4: the cone-frustum path measured with a ballbar square to the cone surface.
#include "mtacc/measurement/measurement.hpp"
#include "mtacc/procedures/cone.hpp"

namespace mtacc {

// The tool ball follows the cone path (TCP); the work ball sits where the surface normals along
// the path meet.
MeasurementRun ballbarCone(const KinematicModel& nominal, const ConeSpec& spec, int points, const ConeDrive& drive);

}  // namespace mtacc
