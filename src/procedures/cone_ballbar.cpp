#include "mtacc/procedures/cone_ballbar.hpp"

namespace mtacc {

MeasurementRun ballbarCone(const KinematicModel& nominal, const ConeSpec& spec, int points, const ConeDrive& drive) {
  const auto path = conePath(spec, points);
  const auto motion = coneMotion(nominal, spec, path, drive);
  // The point nearest to all normal lines (they meet on the cone axis).
  Mat3 a = Mat3::Zero();
  Vec3 b = Vec3::Zero();
  for (size_t i = 0; i < path.points.size(); ++i) {
    const Mat3 p = Mat3::Identity() - path.normals[i] * path.normals[i].transpose();
    a += p;
    b += p * path.points[i];
  }
  const Vec3 w = a.ldlt().solve(b);
  MeasurementRun run;
  run.name = "cone";
  run.instrument = Instrument::Ballbar;
  run.setup.target = w;
  run.setup.length = (path.points[0] - w).norm();
  run.feed = drive.feed;
  run.q = motion.q;
  run.direction = motion.direction;
  run.angle = path.phi;
  run.sense.assign(path.phi.size(), 1);
  return run;
}

}  // namespace mtacc
