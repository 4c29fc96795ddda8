#include "mtacc/procedures/geometric_tests.hpp"

#include <cmath>

#include <Eigen/Dense>

#include "mtacc/core/input_error.hpp"

namespace mtacc {
namespace {

double spread(const Eigen::VectorXd& v) { return v.maxCoeff() - v.minCoeff(); }

}  // namespace

const char* toleranceTestName(GeometricTestKind kind) {
  switch (kind) {
    case GeometricTestKind::Straightness:
      return "straightness";
    case GeometricTestKind::Angular:
      return "angular_deviation";
    case GeometricTestKind::Positional:
      return "positional_deviation";
  }
  return "straightness";
}

GeometricTestResult evaluateGeometricTest(const Machine& machine, const MotionComponent& component, const ComponentRuns& runs) {
  const Axis& axis = machine.axes[static_cast<size_t>(component.axis)];
  if (axis.isRotary()) throw InvalidInput("ISO 230-1's straightness and angular tests are of a linear axis; " + axis.name + " turns");
  GeometricTestResult r;
  const int c = component.component;
  r.kind = c >= 3 ? GeometricTestKind::Angular : c == axis.ownComponent() ? GeometricTestKind::Positional : GeometricTestKind::Straightness;
  r.component = std::string("E") + "XYZABC"[c] + axis.name;
  const auto curve = averageRuns(runs);
  r.positions = curve.positions;
  r.mean = curve.mean;
  r.measuredLength = r.positions.back() - r.positions.front();
  r.repeatability = curve.scatter.maxCoeff();
  r.readingsPerPosition = static_cast<int>(runs.forward.cols() + runs.backward.cols());
  if (r.kind != GeometricTestKind::Straightness) {
    r.quantities.push_back({"range", spread(r.mean)});
    return r;
  }
  const Eigen::Index n = r.mean.size();
  Eigen::VectorXd x(n);
  for (Eigen::Index i = 0; i < n; ++i) x[i] = r.positions[static_cast<size_t>(i)];
  const double endSlope = (r.mean[n - 1] - r.mean[0]) / (x[n - 1] - x[0]);
  r.endPointResidual = r.mean - (r.mean[0] + endSlope * (x.array() - x[0])).matrix();
  Eigen::MatrixXd design(n, 2);
  design.col(0).setOnes();
  design.col(1) = x;
  const Eigen::Vector2d line = design.colPivHouseholderQr().solve(r.mean);
  r.leastSquaresSlope = line[1];
  r.leastSquaresResidual = r.mean - design * line;
  r.quantities.push_back({"end_point", spread(r.endPointResidual)});
  r.quantities.push_back({"least_squares", spread(r.leastSquaresResidual)});
  return r;
}

}  // namespace mtacc
