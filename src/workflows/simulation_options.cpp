#include "mtacc/workflows/simulation_options.hpp"

#include "mtacc/core/text.hpp"

namespace mtacc {
namespace {

// The ranges of most values are checked where the path is built, which names the key.
std::vector<OptionField> commonFields(const std::string& output) {
  return {{"noise", OptionKind::Quantity, "Standard deviation of Gaussian reading noise", "0 um"},
          {.key = "seed", .kind = OptionKind::Count, .help = "Random seed of the noise", .defaultText = "1", .low = 0, .high = 2147483647,
           .outOfRange = "must be from 0 to 2147483647"},
          {"setup", OptionKind::Text, "Set-up errors, e.g. xW=10um,zT=-5um (xT yT zT xW yW zW aN bN cN dL)"},
          {"output", OptionKind::Text, output}};
}

OptionField toolBallField() { return {"tool_ball", OptionKind::Text, "Ball centre relative to the TCP in the tool frame, mm, e.g. 0,0,-50", "0,0,0"}; }
OptionField poseField() { return {"pose", OptionKind::Text, "The other axes, e.g. B=-30 (deg, mm; others 0)"}; }

OptionSchema withCommon(std::string name, const std::string& output, std::vector<OptionField> own) {
  OptionSchema schema{std::move(name), commonFields(output)};
  schema.fields.insert(schema.fields.end(), own.begin(), own.end());
  return schema;
}

SimulationOptions simulationOptions(const OptionReader& read, const Machine& machine, const OptionSchema& schema, bool folder) {
  SimulationOptions s;
  s.noise = *read.quantity("noise");
  s.seed = static_cast<std::uint64_t>(*read.count("seed"));
  s.setupErrors = parseSetupErrors(read.text("setup").value_or(""), "setup");
  if (schema.find("lag"))
    s.disturbance = disturbanceFromText(machine, read.text("lag").value_or(""), read.text("backlash").value_or(""),
                                        read.text("spike").value_or(""), *read.number("spike_time"));
  s.output = read.text("output").value_or("");
  s.outputIsFolder = folder;
  return s;
}

std::vector<double> poseOf(const MachineSetup& setup, const OptionReader& read) {
  const auto pose = read.text("pose");
  return pose && !pose->empty() ? poseFromText(setup, *pose, "pose", true) : std::vector<double>{};
}

}  // namespace

const OptionSchema& ballbarSimulationSchema() {
  static const OptionSchema schema = withCommon(
      "simulate ballbar", "CSV file to write",
      {toolBallField(),
       {"plane", OptionKind::Text, "XY, YZ or ZX", "XY"},
       {"centre", OptionKind::Text, "Centre ball in the workpiece frame, mm", "0,0,0"},
       {"radius", OptionKind::Quantity, "Bar length", "100 mm"},
       {"points", OptionKind::Count, "Points per direction", "360"},
       {"feed", OptionKind::Number, "Feed, mm/min", "1000"},
       poseField(),
       {"one_direction", OptionKind::Flag, "Counter-clockwise only"},
       {"lag", OptionKind::Text, "Following error per axis (1/kv), e.g. X=1ms"},
       {"backlash", OptionKind::Text, "Lost motion per axis, e.g. X=5um"},
       {"spike", OptionKind::Text, "Reversal spike height per axis, e.g. Y=4um"},
       {"spike_time", OptionKind::Number, "Decay time of the reversal spikes, s", "0.02"}});
  return schema;
}

const OptionSchema& rtestSimulationSchema() {
  static const OptionSchema schema = withCommon(
      "simulate rtest", "CSV file to write",
      {toolBallField(),
       {"axis", OptionKind::Text, "Rotary axis that steps", "C"},
       {.key = "from", .kind = OptionKind::Quantity, .help = "First angle", .defaultText = "0 deg", .dimension = Dimension::Angle},
       {.key = "to", .kind = OptionKind::Quantity, .help = "Last angle", .defaultText = "330 deg", .dimension = Dimension::Angle},
       {.key = "points", .kind = OptionKind::Count, .help = "Number of angles", .defaultText = "12", .low = 1, .high = kMaxPointsPerRun,
        .outOfRange = "must be from 1 to 100000"},
       {.key = "sphere", .kind = OptionKind::Text, .help = "Sphere centre in the workpiece frame, mm", .required = true},
       poseField(),
       {"probe", OptionKind::Flag, "Touch-probe readings instead of the R-test's"}});
  return schema;
}

const OptionSchema& planSimulationSchema() {
  static const OptionSchema schema = withCommon(
      "simulate plan", "Directory to write the CSV files into",
      {{.key = "plan", .kind = OptionKind::Text, .help = "Test plan (YAML) or bundled plan name", .required = true}});
  return schema;
}

SimulationResult simulateBallbar(const MachineSetup& setup, const OptionValues& values) {
  const OptionReader read(ballbarSimulationSchema(), values);
  BallbarCircleSpec spec;
  spec.plane = *read.text("plane");
  spec.centre = parseVector(*read.text("centre"), "centre");
  spec.radius = *read.quantity("radius");
  spec.points = *read.count("points");
  spec.feed = *read.number("feed");
  spec.bothDirections = !read.flag("one_direction");
  spec.toolBall = parseVector(*read.text("tool_ball"), "tool_ball");
  spec.pose = poseOf(setup, read);
  return simulateBallbarCircle(setup, spec, simulationOptions(read, *setup.machine, ballbarSimulationSchema(), false));
}

SimulationResult simulateRTest(const MachineSetup& setup, const OptionValues& values) {
  const OptionReader read(rtestSimulationSchema(), values);
  SphereTestSpec spec;
  spec.instrument = read.flag("probe") ? Instrument::TouchProbe : Instrument::RTest;
  spec.axis = *read.text("axis");
  spec.angles = evenAngles(*read.quantity("from"), *read.quantity("to"), *read.count("points"));
  spec.spheres = {parseVector(*read.text("sphere"), "sphere")};
  spec.toolBall = parseVector(*read.text("tool_ball"), "tool_ball");
  spec.pose = poseOf(setup, read);
  return simulateSphereTest(setup, spec, simulationOptions(read, *setup.machine, rtestSimulationSchema(), false));
}

SimulationResult simulatePlanRuns(const MachineSetup& setup, const OptionValues& values) {
  const OptionReader read(planSimulationSchema(), values);
  return simulatePlan(setup, *read.text("plan"), simulationOptions(read, *setup.machine, planSimulationSchema(), true));
}

}  // namespace mtacc
