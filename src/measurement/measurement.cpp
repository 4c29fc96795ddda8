#include "mtacc/measurement/measurement.hpp"

#include <array>

#include "mtacc/core/input_error.hpp"

namespace mtacc {
namespace {

constexpr std::array<const char*, kSetupParameterCount> kSetupNames = {"xT", "yT", "zT", "xW", "yW",
                                                                       "zW", "aN", "bN", "cN", "dL"};

double err(const MeasurementRun& run, SetupParameter p) { return run.setup.errors[static_cast<size_t>(p)]; }

Vec3 targetError(const MeasurementRun& run) {
  return Vec3(err(run, SetupParameter::TargetX), err(run, SetupParameter::TargetY), err(run, SetupParameter::TargetZ));
}
Vec3 actualToolBall(const KinematicModel& model, const MeasurementRun& run, const double* q, const int* dir) {
  return toolInWorkpiece(model, q, dir) * toolBallWithSetupError(run);
}
const int* dirRow(const MeasurementRun& run, Eigen::Index i) { return run.direction.size() ? run.direction.row(i).data() : nullptr; }

}  // namespace

std::string instrumentName(Instrument instrument) {
  switch (instrument) {
    case Instrument::Ballbar: return "ballbar";
    case Instrument::RTest: return "rtest";
    case Instrument::TouchProbe: return "probe";
    case Instrument::Directional: return "directional";
  }
  return "";
}

std::optional<Instrument> parseInstrument(const std::string& name) {
  for (auto i : {Instrument::Ballbar, Instrument::RTest, Instrument::TouchProbe, Instrument::Directional})
    if (instrumentName(i) == name) return i;
  return std::nullopt;
}

std::string travelViolation(const Machine& m, const MeasurementRun& run) {
  for (Eigen::Index i = 0; i < run.poses(); ++i) {
    const std::vector<double> pose(run.q.row(i).data(), run.q.row(i).data() + run.q.cols());
    if (auto violation = m.travelViolation(pose); !violation.empty())
      return "pose " + std::to_string(i + 1) + " of " + std::to_string(run.poses()) + ": " + violation;
  }
  return {};
}

int readingSize(Instrument instrument) {
  return instrument == Instrument::RTest || instrument == Instrument::TouchProbe ? 3 : 1;
}

std::string setupParameterName(SetupParameter p) { return kSetupNames[static_cast<size_t>(p)]; }

std::optional<SetupParameter> parseSetupParameter(const std::string& name) {
  for (size_t i = 0; i < kSetupNames.size(); ++i)
    if (name == kSetupNames[i]) return static_cast<SetupParameter>(i);
  return std::nullopt;
}

bool appliesTo(SetupParameter p, Instrument instrument) {
  switch (p) {
    case SetupParameter::NestA:
    case SetupParameter::NestB:
    case SetupParameter::NestC: return instrument == Instrument::RTest;
    case SetupParameter::Length: return instrument == Instrument::Ballbar;
    case SetupParameter::TargetX:
    case SetupParameter::TargetY:
    case SetupParameter::TargetZ: return instrument != Instrument::Directional;
    default: return true;
  }
}

Dimension setupParameterDimension(SetupParameter p) {
  return p == SetupParameter::NestA || p == SetupParameter::NestB || p == SetupParameter::NestC ? Dimension::Angle
                                                                                                : Dimension::Length;
}

Vec3 toolBallWithSetupError(const MeasurementRun& run) {
  return run.setup.toolBall +
         Vec3(err(run, SetupParameter::ToolBallX), err(run, SetupParameter::ToolBallY), err(run, SetupParameter::ToolBallZ));
}

Vec3 workBall(const KinematicModel& model, const MeasurementRun& run) {
  const Vec3 base = run.setup.setAt ? actualToolBall(model, run, run.setup.setAt->data(), nullptr) : run.setup.target;
  return base + targetError(run);
}

RunGeometry runGeometry(const KinematicModel& model, const MeasurementRun& run) {
  RunGeometry g;
  g.toolBall = toolBallWithSetupError(run);
  g.target = run.instrument == Instrument::Ballbar ? workBall(model, run) : Vec3(run.setup.target + targetError(run));
  if (run.instrument == Instrument::RTest) {
    const double a = err(run, SetupParameter::NestA), b = err(run, SetupParameter::NestB), c = err(run, SetupParameter::NestC);
    g.nestTranspose = rotationXYZ(a, b, c).transpose();
    for (int k = 0; k < 3; ++k) g.nestTransposeDerivatives[static_cast<size_t>(k)] = rotationXYZDerivative(a, b, c, k).transpose();
  }
  g.length = run.setup.length + err(run, SetupParameter::Length);
  return g;
}

NominalFrame nominalFrame(const KinematicModel& nominal, const MeasurementRun& run, Eigen::Index i) {
  const double* q = run.q.row(i).data();
  NominalFrame f;
  switch (run.instrument) {
    case Instrument::RTest:
    case Instrument::TouchProbe: f.workpieceRotation = workpiecePose(nominal, q, nullptr).linear(); break;
    case Instrument::Directional: f.toolBall = toolInWorkpiece(nominal, q) * run.setup.toolBall; break;
    case Instrument::Ballbar: break;
  }
  return f;
}

Reading predictReading(const KinematicModel& model, const KinematicModel& nominal, const MeasurementRun& run, Eigen::Index i) {
  return predictReading(model, {run, i, runGeometry(model, run), nominalFrame(nominal, run, i)});
}

Reading predictReading(const KinematicModel& model, const ReadingContext& reading) {
  const MeasurementRun& run = reading.run;
  const Eigen::Index i = reading.pose;
  const RunGeometry& geometry = reading.geometry;
  const NominalFrame& nominal = reading.nominal;
  const Vec3 t = toolInWorkpiece(model, run.q.row(i).data(), dirRow(run, i)) * geometry.toolBall;
  Reading r(readingSize(run.instrument));
  switch (run.instrument) {
    case Instrument::Ballbar: r[0] = (t - geometry.target).norm() - geometry.length; break;
    case Instrument::RTest: r = nominal.workpieceRotation * (geometry.nestTranspose * (t - geometry.target)); break;
    case Instrument::TouchProbe: r = -(nominal.workpieceRotation * (t - geometry.target)); break;
    case Instrument::Directional: r[0] = run.setup.direction.dot(t - nominal.toolBall); break;
  }
  return r;
}

Eigen::MatrixXd predictReadings(const KinematicModel& model, const KinematicModel& nominal, const MeasurementRun& run,
                                int threads) {
  Eigen::MatrixXd out(run.poses(), readingSize(run.instrument));
  const RunGeometry geometry = runGeometry(model, run);
  parallelFor(run.poses(), threads, [&](long b, long e) {
    for (long i = b; i < e; ++i) out.row(i) = predictReading(model, {run, i, geometry, nominalFrame(nominal, run, i)}).transpose();
  });
  return out;
}

void readingJacobian(const KinematicModel& model, const ReadingContext& reading, KinematicData& data, ReadingJacobian& out) {
  const auto& [run, i, geometry, nominal, setupParameters, setAtJacobian] = reading;
  const PointJacobian& pj = pointJacobian(model, run.q.row(i).data(), dirRow(run, i), geometry.toolBall, data);
  const Vec3& t = pj.point;
  // d(tool ball)/d(xT yT zT): the tool frame's rotation in the workpiece frame.
  const Mat3& toolRotation = pj.toolRotation;
  const int m = readingSize(run.instrument);
  out.machine.resize(m, static_cast<Eigen::Index>(model.parameters.size()));
  out.setup.setZero(m, static_cast<Eigen::Index>(setupParameters.size()));
  out.reading.resize(m);

  // Every reading is (a linear map of) the tool ball minus a target point; `sensitivity`
  // is the map (its first m rows; fixed-size so that the products below are unrolled).
  Mat3 sensitivity = Mat3::Zero();
  const PointJacobian* target = nullptr;  // d(target)/d(machine): a ballbar set at the tool ball
  Mat3 targetToolRotation = Mat3::Zero();  // d(target)/d(xT yT zT): a ballbar set at the tool ball
  switch (run.instrument) {
    case Instrument::Ballbar: {
      if (run.setup.setAt && !setAtJacobian)
        throw InvalidInput("readingJacobian: a ballbar set at the tool ball needs the point Jacobian there");
      const Vec3 u = (t - geometry.target).normalized();
      out.reading[0] = (t - geometry.target).norm() - geometry.length;
      sensitivity.row(0) = u.transpose();
      if (run.setup.setAt) {
        target = setAtJacobian;
        targetToolRotation = setAtJacobian->toolRotation;
      }
      break;
    }
    case Instrument::RTest:
    case Instrument::TouchProbe: {
      const Mat3& r = nominal.workpieceRotation;
      const Vec3 rel = t - geometry.target;
      const bool rTest = run.instrument == Instrument::RTest;
      sensitivity = rTest ? Mat3(r * geometry.nestTranspose) : Mat3(-r);
      out.reading = sensitivity * rel;
      if (!rTest) break;
      for (size_t k = 0; k < setupParameters.size(); ++k) {
        const auto p = setupParameters[k];
        if (p != SetupParameter::NestA && p != SetupParameter::NestB && p != SetupParameter::NestC) continue;
        const auto which = static_cast<size_t>(p) - static_cast<size_t>(SetupParameter::NestA);
        out.setup.col(static_cast<Eigen::Index>(k)) = r * (geometry.nestTransposeDerivatives[which] * rel);
      }
      break;
    }
    case Instrument::Directional:
      sensitivity.row(0) = run.setup.direction.transpose();
      out.reading[0] = run.setup.direction.dot(t - nominal.toolBall);
      break;
  }
  for (int row = 0; row < m; ++row) {
    out.machine.row(row).noalias() = sensitivity.row(row).lazyProduct(pj.jacobian);
    if (target) out.machine.row(row).noalias() -= sensitivity.row(row).lazyProduct(target->jacobian);
  }
  for (size_t k = 0; k < setupParameters.size(); ++k) {
    const auto p = setupParameters[k];
    const auto col = static_cast<Eigen::Index>(k);
    if (!appliesTo(p, run.instrument)) continue;
    if (p <= SetupParameter::ToolBallZ) {
      const Vec3 d = (toolRotation - targetToolRotation).col(static_cast<int>(p));
      out.setup.col(col) = (sensitivity * d).head(m);
    } else if (p <= SetupParameter::TargetZ) {
      out.setup.col(col) = -sensitivity.col(static_cast<int>(p) - static_cast<int>(SetupParameter::TargetX)).head(m);
    } else if (p == SetupParameter::Length) {
      out.setup(0, col) = -1.0;
    }
  }
}

}  // namespace mtacc
