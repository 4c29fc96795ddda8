#pragma once
// What an instrument reads at a sequence of machine poses, on any machine with its errors:
// the ballbar (seed 002, ISO 230-4), the R-test / CapBall (ISO 10791-6), a touch probe on a
// sphere at rotary-axis indexes, and a directional probe (the TCP deviation along a given
// direction; the model behind machined features such as seed 001's cubic zones).
// Lengths in mm, angles in rad; every point lives in the workpiece frame unless stated.
#include <array>
#include <optional>
#include <span>
#include <string>
#include <vector>

#include "mtacc/core/transform.hpp"
#include "mtacc/errors/error_model.hpp"
#include "mtacc/kinematics/forward.hpp"
#include "mtacc/kinematics/jacobian.hpp"

namespace mtacc {

enum class Instrument { Ballbar, RTest, TouchProbe, Directional };
// "ballbar", "rtest", "probe", "directional"
std::string instrumentName(Instrument instrument);
std::optional<Instrument> parseInstrument(const std::string& name);
// Readings per pose: ballbar and directional 1 (mm), R-test and probe 3 (mm, machine axes).
int readingSize(Instrument instrument);

// Set-up errors of one run, the parameters an identification may estimate besides the
// machine's. Names as in seed 002 §6 (Eqs 15-16) for both ball instruments.
enum class SetupParameter {
  ToolBallX, ToolBallY, ToolBallZ,  // xT yT zT: ball centre offset from its nominal, tool frame
  TargetX, TargetY, TargetZ,        // xW yW zW: work ball / sphere on the nest, workpiece frame
  NestA, NestB, NestC,              // aN bN cN: R-test sensor nest orientation (rad)
  Length,                           // dL: ballbar length error (mm)
};
constexpr int kSetupParameterCount = 10;
std::string setupParameterName(SetupParameter p);  // "xT", ..., "dL"
std::optional<SetupParameter> parseSetupParameter(const std::string& name);
bool appliesTo(SetupParameter p, Instrument instrument);
Dimension setupParameterDimension(SetupParameter p);

struct Setup {
  // Nominal ball centre (or probe tip, or the point whose deviation a directional probe
  // reads) relative to the TCP, in the tool frame.
  Vec3 toolBall = Vec3::Zero();
  // Ballbar: the work ball; R-test / probe: the sphere (R-test: the nest centre). Ignored
  // by the ballbar when setAt is given.
  Vec3 target = Vec3::Zero();
  // Ballbar only: the work ball is set where the actual tool ball is at this pose (seed 002
  // Eqs 11-12), e.g. the start pose; plus the xW yW zW mounting error.
  std::optional<std::vector<double>> setAt;
  double length = 0.0;           // ballbar nominal length L (mm)
  Vec3 direction = Vec3::UnitZ();  // directional probe: unit sensing direction
  // The set-up errors, indexed by SetupParameter.
  std::array<double, kSetupParameterCount> errors{};
};

// One measurement run: its poses (and the directions of motion, for reversal errors) and
// readings. `angle` is the plot angle of each sample (rad) in the plot plane spanned by
// plotAxes (machine frame), for circular tests; empty otherwise.
struct MeasurementRun {
  std::string name;
  Instrument instrument = Instrument::Ballbar;
  Setup setup;
  JointMatrix q;
  DirectionMatrix direction;  // empty or like q
  Eigen::MatrixXd readings;   // poses x readingSize, mm; empty until simulated or read
  std::vector<double> angle;
  std::vector<int> sense;     // +1 counter-clockwise, -1 clockwise in the plot plane (ballbar)
  std::array<Vec3, 2> plotAxes{Vec3::UnitX(), Vec3::UnitY()};
  double feed = 1000.0;       // mm/min along the path, for the disturbance models
  // Standard deviation of the reading noise (mm) as the instrument's user states it, for the
  // goodness-of-fit test of an identification; unset when not stated.
  std::optional<double> noise;
  // Set-up errors an identification estimates for this run (the others stay as given).
  std::vector<SetupParameter> estimate;

  Eigen::Index poses() const { return q.rows(); }
};

// "pose 12 of 146: X=500 mm beyond travel [-400, 400] mm" for the run's first pose outside
// the machine's travel; empty when every pose is within.
std::string travelViolation(const Machine& m, const MeasurementRun& run);

// One reading: 3 values (R-test, touch probe) or 1 (ballbar, directional probe), mm.
using Reading = Eigen::Matrix<double, Eigen::Dynamic, 1, 0, 3, 1>;

// What a reading takes from the nominal machine at one pose, constant while errors are
// identified: the nominal workpiece rotation (R-test and probe readings are turned into
// machine axes with it) or the nominal tool ball (the directional probe's reference).
struct NominalFrame {
  Mat3 workpieceRotation = Mat3::Identity();
  Vec3 toolBall = Vec3::Zero();
};
NominalFrame nominalFrame(const KinematicModel& nominal, const MeasurementRun& run, Eigen::Index i);

// What a reading takes from the run's set-up at its current set-up errors, the same at every
// pose (computed once per run rather than at each pose).
struct RunGeometry {
  Vec3 toolBall = Vec3::Zero();  // toolBallWithSetupError
  Vec3 target = Vec3::Zero();    // work ball, sphere or probed sphere with its xW yW zW error, workpiece frame
  Mat3 nestTranspose = Mat3::Identity();  // R-test: N^T, N the nest orientation (aN bN cN)
  std::array<Mat3, 3> nestTransposeDerivatives{};  // R-test: dN^T / d(aN, bN, cN)
  double length = 0.0;           // ballbar: L + dL
};
RunGeometry runGeometry(const KinematicModel& model, const MeasurementRun& run);

// The readings the instrument shows at pose i of the run on `model` (exact model,
// including the run's set-up errors).
Reading predictReading(const KinematicModel& model, const KinematicModel& nominal, const MeasurementRun& run, Eigen::Index i);
Eigen::MatrixXd predictReadings(const KinematicModel& model, const KinematicModel& nominal, const MeasurementRun& run,
                                int threads = kAllCores);

// Reading and its derivative with respect to machine parameters and set-up parameters
// (row-major: each reading's derivatives side by side, as stacked systems store them).
using ReadingRows = Eigen::Matrix<double, Eigen::Dynamic, Eigen::Dynamic, Eigen::RowMajor, 3, Eigen::Dynamic>;
struct ReadingJacobian {
  Reading reading;
  ReadingRows machine;  // readingSize x machine parameters
  ReadingRows setup;    // readingSize x setup parameters
};
// One reading: pose `pose` of `run`, with what is fixed per run and per pose, and for its
// derivatives the set-up parameters to differentiate by.
struct ReadingContext {
  const MeasurementRun& run;
  Eigen::Index pose;
  const RunGeometry& geometry;  // runGeometry(model, run)
  const NominalFrame& nominal;  // nominalFrame(nominal model, run, pose)
  std::span<const SetupParameter> setupParameters = {};
  // pointJacobian of toolBallWithSetupError(run) at run.setup.setAt, computed once per run
  // by the caller: required for the derivatives of a ballbar set at the tool ball
  // (InvalidInput otherwise), ignored else.
  const PointJacobian* setAt = nullptr;
};
// The same as predictReading, from what is fixed per run and per pose (many poses).
Reading predictReading(const KinematicModel& model, const ReadingContext& reading);
// The reading and its derivatives into `out`, reusing its storage (identifications call this
// once per reading). The machine parameters are the model's (compile's jacobianParameters).
void readingJacobian(const KinematicModel& model, const ReadingContext& reading, KinematicData& data, ReadingJacobian& out);

// The work ball of a ballbar run in the workpiece frame (set-up error included).
Vec3 workBall(const KinematicModel& model, const MeasurementRun& run);
// The tool ball relative to the TCP in the tool frame, set-up error xT yT zT included (the
// point whose pointJacobian at setAt readingJacobian expects).
Vec3 toolBallWithSetupError(const MeasurementRun& run);

}  // namespace mtacc
