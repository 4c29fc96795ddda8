#include "mtacc/workflows/kinematics_options.hpp"

#include "mtacc/core/input_error.hpp"
#include "mtacc/core/text.hpp"

namespace mtacc {
namespace {

OptionField poseOption() { return {"pose", OptionKind::Text, "axis positions, e.g. X=10,Y=0,Z=5,B=-15,C=30 (mm, deg)"}; }
// Empty text counts as not given, as an option left out does ("--pose ''").
std::optional<std::string> givenText(const OptionReader& read, const char* key) {
  auto text = read.text(key);
  return text && !text->empty() ? text : std::nullopt;
}

OptionField posesOption() { return {"poses", OptionKind::Text, "CSV with one column per axis (mm, deg), optional <axis>_dir columns"}; }

}  // namespace

const OptionSchema& forwardSchema() {
  static const OptionSchema schema{"fk", {poseOption(), posesOption(), {"nominal", OptionKind::Flag, "ignore the errors (nominal machine)"}, threadsOption()}};
  return schema;
}

const OptionSchema& errorsSchema() {
  static const OptionSchema schema{
      "errors",
      {poseOption(), posesOption(), {"with_tcp", OptionKind::Flag, "also the TCP (mm) and tool direction columns, as fk prints them"}, threadsOption()}};
  return schema;
}

const OptionSchema& inverseSchema() {
  static const OptionSchema schema{
      "ik",
      {{"tcp", OptionKind::Text, "TCP position x,y,z in the workpiece frame (mm)"},
       {"tool", OptionKind::Text, "tool direction i,j,k (TCP towards spindle)", "0,0,1"},
       {"targets", OptionKind::Text, "CSV with columns x,y,z,i,j,k: solved as a continuous path"},
       {"branch", OptionKind::Text, "tilt branch of the first pose: auto, positive or negative", "auto"},
       {"near", OptionKind::Text,
        "a pose to stay near, e.g. B=30,C=170 (mm, deg; axes not named 0): rotary angles closest to it, a free angle at a singular pose "
        "kept at its value"},
       {"with_errors", OptionKind::Flag,
        "the commands that reach the pose on the machine with its errors (the inverse error model), with the residual"},
       {"all", OptionKind::Flag, "list every solution of a single target (including those beyond travel)"}}};
  return schema;
}

ForwardOptions forwardOptions(const OptionSchema& schema, const OptionValues& values) {
  const OptionReader read(schema, values);
  ForwardOptions o;
  if (schema.find("nominal")) o.nominal = read.flag("nominal");
  o.threads = *read.count("threads");
  return o;
}

ForwardResult forwardKinematicsOf(const MachineSetup& setup, const OptionSchema& schema, const OptionValues& values) {
  const OptionReader read(schema, values);
  const auto pose = givenText(read, "pose"), poses = givenText(read, "poses");
  if (pose.has_value() == poses.has_value())
    throw InputError(InputLocation{"", 0, "--pose/--poses"}, "give exactly one of --pose AXIS=VALUE,... or --poses FILE.csv");
  const ForwardOptions options = forwardOptions(schema, values);
  if (poses) return forwardKinematicsOfFile(setup, *poses, options);
  const auto q = poseFromText(setup, *pose, "pose");
  return forwardKinematics(setup, Eigen::Map<const JointMatrix>(q.data(), 1, static_cast<Eigen::Index>(q.size())), {}, options);
}

InverseRequest inverseSolving(const MachineSetup& setup, const OptionValues& values) {
  const OptionReader read(inverseSchema(), values);
  InverseRequest r;
  r.options.branch = parseTiltBranch(*read.text("branch"));
  if (const auto near = givenText(read, "near")) r.options.hint = poseFromText(setup, *near, "near", true);
  r.all = read.flag("all");
  r.withErrors = read.flag("with_errors");
  return r;
}

InverseRequest inverseRequest(const MachineSetup& setup, const OptionValues& values) {
  const OptionReader read(inverseSchema(), values);
  const auto tcp = givenText(read, "tcp"), targets = givenText(read, "targets");
  if (tcp.has_value() == targets.has_value())
    throw InputError(InputLocation{"", 0, "--tcp/--targets"}, "give exactly one of --tcp x,y,z or --targets FILE.csv");
  InverseRequest r = targets ? inverseTargetsOfFile(*targets) : InverseRequest{};
  const InverseRequest solving = inverseSolving(setup, values);
  r.options = solving.options;
  r.all = solving.all;
  r.withErrors = solving.withErrors;
  if (tcp) {
    r.positions.push_back(parseVector(*tcp, "tcp"));
    r.directions.push_back(parseVector(*read.text("tool"), "tool"));
  }
  return r;
}

}  // namespace mtacc
