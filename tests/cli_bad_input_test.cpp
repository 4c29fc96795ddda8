// Bad input through the CLI: one line on stderr naming file, line and key (or the pose), a
// non-zero exit, and no output file.
#include <gtest/gtest.h>

#include <sys/wait.h>

#include <algorithm>
#include <cstdlib>
#include <filesystem>
#include <fstream>
#include <sstream>
#include <string>

#include "test_helpers.hpp"
#include "test_paths.hpp"

namespace {

namespace fs = std::filesystem;

struct CliRun {
  int exitCode;
  std::string out;
  std::string err;
};

class CliBadInput : public ::testing::Test {
 protected:
  std::string write(const std::string& name, const std::string& text) {
    const auto p = dir_ / name;
    std::ofstream(p) << text;
    return p.string();
  }
  static std::string slurp(const fs::path& p) {
    std::ifstream in(p);
    std::stringstream s;
    s << in.rdbuf();
    return s.str();
  }
  CliRun run(const std::string& args) {
    const auto out = dir_ / "stdout.txt", err = dir_ / "stderr.txt";
    const std::string cmd = mtacc::test::cliPath() + " " + args + " > " + out.string() + " 2> " + err.string();
    const int status = std::system(cmd.c_str());
    return {WEXITSTATUS(status), slurp(out), slurp(err)};
  }
  std::string output() const { return (dir_ / "result.csv").string(); }
  // One line, the expected pieces in it, non-zero exit, no output file.
  void expectCleanFailure(const CliRun& r, std::initializer_list<std::string> pieces) {
    EXPECT_NE(r.exitCode, 0);
    EXPECT_EQ(std::count(r.err.begin(), r.err.end(), '\n'), 1) << r.err;
    for (const auto& p : pieces) EXPECT_NE(r.err.find(p), std::string::npos) << "missing '" << p << "' in: " << r.err;
    EXPECT_FALSE(fs::exists(output()));
    for (const auto& e : fs::directory_iterator(dir_)) EXPECT_EQ(e.path().string().find(".tmp"), std::string::npos);
  }

  mtacc::test::TestFolder folder_{"mtacc-cli"};
  const fs::path dir_ = folder_.dir();
};

// The bad-input cases of the C++ and Python tests start from the same small machine.
const std::string kMachine = [] {
  std::ifstream in(mtacc::test::testDataDir() + "/test-machine.yaml");
  std::stringstream s;
  s << in.rdbuf();
  return s.str();
}();

TEST_F(CliBadInput, MalformedYaml) {
  const auto f = write("bad.yaml", "name: x\naxes: [1, 2\nstructure: t-Z-b-X-w\n");
  expectCleanFailure(run("check " + f + " -o " + output()), {f + ":", "malformed YAML"});
}

TEST_F(CliBadInput, UnknownAxisLetterInStructureCode) {
  const auto f = write("m.yaml", "name: x\nstructure: t-(C)-Z-Q-b-X-w\naxes: {}\n");
  expectCleanFailure(run("check " + f + " -o " + output()), {f + ":2: structure", "unknown letter 'Q'"});
}

TEST_F(CliBadInput, AxisEntryNotInStructureCode) {
  const auto f = write("m.yaml", kMachine + "  A: {direction: [1, 0, 0], travel: [0 deg, 90 deg]}\n");
  expectCleanFailure(run("check " + f + " -o " + output()), {f + ":9: axes.A", "not in the structure code"});
}

TEST_F(CliBadInput, UnknownErrorName) {
  const auto f = write("m.yaml", kMachine + "errors:\n  X0Q: 10 um\n");
  expectCleanFailure(run("check " + f + " -o " + output()), {f + ":10: errors.X0Q", "unknown error parameter"});
}

TEST_F(CliBadInput, UnknownComponentErrorAxis) {
  const auto f = write("m.yaml", kMachine + "errors:\n  EXQ: 10 um\n");
  expectCleanFailure(run("check " + f + " -o " + output()), {f + ":10: errors.EXQ", "unknown error parameter"});
}

TEST_F(CliBadInput, MissingUnit) {
  const auto f = write("m.yaml", kMachine + "errors:\n  X0C: 10\n");
  expectCleanFailure(run("budget " + f + " -o " + output()), {f + ":10: errors.X0C", "missing unit"});
}

TEST_F(CliBadInput, WrongDimension) {
  const auto f = write("m.yaml", kMachine + "errors:\n  A0C: 10 um\n");
  expectCleanFailure(run("check " + f + " -o " + output()), {f + ":10: errors.A0C", "expected an angle but '10 um' is a length"});
}

TEST_F(CliBadInput, ZeroDirectionVector) {
  std::string m = kMachine;
  m.replace(m.find("[1, 0, 0]"), 9, "[0, 0, 0]");
  const auto f = write("m.yaml", m);
  expectCleanFailure(run("check " + f + " -o " + output()), {f + ":4: axes.X.direction", "zero length"});
}

TEST_F(CliBadInput, UnreachableToolDirection) {
  const auto f = write("m.yaml", kMachine);
  expectCleanFailure(run("ik " + f + " --tcp 0,0,0 --tool 0,0,-1 -o " + output()), {"--tcp: unreachable", "tool (0, 0, -1)", "B=180 deg beyond travel"});
}

TEST_F(CliBadInput, TcpBeyondTravel) {
  const auto f = write("m.yaml", kMachine);
  expectCleanFailure(run("ik " + f + " --tcp 1000,0,0 --tool 0,0,1 -o " + output()), {"TCP (1000, 0, 0)", "X=1000 mm beyond travel [-400, 400] mm"});
}

TEST_F(CliBadInput, PoseFileBeyondTravel) {
  const auto f = write("m.yaml", kMachine);
  const auto p = write("poses.csv", "X,Y,Z,B,C\n10,20,30,-15,45\n500,0,0,0,0\n");
  expectCleanFailure(run("fk " + f + " --poses " + p + " -o " + output()), {p + ":3", "X=500 mm beyond travel"});
}

TEST_F(CliBadInput, PoseFileWithNaNAndWrongColumns) {
  const auto f = write("m.yaml", kMachine);
  const auto p = write("poses.csv", "X,Y,Z,B,C\n10,20,nan,-15,45\n");
  expectCleanFailure(run("errors " + f + " --poses " + p + " -o " + output()), {p + ":2: Z", "not a finite number"});
  const auto q = write("poses2.csv", "X,Y,Z,B,C\n10,20,30,-15\n");
  expectCleanFailure(run("errors " + f + " --poses " + q + " -o " + output()), {q + ":2", "expected 5 columns, found 4"});
}

TEST_F(CliBadInput, GoodInputWritesTheFile) {
  const auto f = write("m.yaml", kMachine + "errors:\n  X0C: 10 um\n");
  const auto r = run("fk " + f + " --pose X=1,Y=2,Z=3,B=10,C=20 -o " + output());
  EXPECT_EQ(r.exitCode, 0) << r.err;
  EXPECT_TRUE(r.err.empty());
  ASSERT_TRUE(fs::exists(output()));
  EXPECT_NE(slurp(output()).find("dx_um"), std::string::npos);
}

// A ballbar export (angle and dL only; the circle named in the header) on the bundled
// 3-axis machine.
std::string ballbarFile(int points, const std::string& badRow = "") {
  std::string t = "# instrument: ballbar\n# length: 100 mm\n# target: 300, 200, 250 mm\n# plane: XY\nangle_deg,dL_um\n";
  for (int i = 0; i < points; ++i) t += std::to_string(360.0 * i / points) + "," + std::to_string(0.1 * (i % 3)) + "\n";
  return t + badRow;
}

TEST_F(CliBadInput, MeasurementFileWithNaNOrWrongColumns) {
  const auto nan = write("nan.csv", ballbarFile(36, "12,nan\n"));
  expectCleanFailure(run("evaluate three-axis-vertical " + nan + " -o " + output()), {nan + ":42: dL_um", "not a finite number"});
  const auto cols = write("cols.csv", ballbarFile(36, "12,0.1,7\n"));
  expectCleanFailure(run("evaluate three-axis-vertical " + cols + " -o " + output()), {cols + ":42", "expected 2 columns, found 3"});
  const auto noInstrument = write("none.csv", "# length: 100 mm\nangle_deg,dL_um\n0,0\n");
  expectCleanFailure(run("evaluate three-axis-vertical " + noInstrument + " -o " + output()), {noInstrument + ":1: instrument", "missing"});
  const auto badUnit = write("unit.csv", "# instrument: ballbar\n# length: 100\n# target: 0, 0, 0 mm\nangle_deg,dL_um\n0,0\n");
  expectCleanFailure(run("evaluate three-axis-vertical " + badUnit + " -o " + output()), {badUnit + ":2: length"});
}

TEST_F(CliBadInput, TooFewPoints) {
  const auto few = write("few.csv", ballbarFile(5));
  expectCleanFailure(run("evaluate three-axis-vertical " + few + " -o " + output()), {few, "too few points"});
  expectCleanFailure(run("identify three-axis-vertical --data " + few + " --params C0Y,A0Z,B0Z,EXX.c1,Y0Y,Z0Z -o " + output()),
                     {"too few readings: 5 for 6 unknowns"});
}

TEST_F(CliBadInput, UnidentifiableSetIsRefused) {
  const auto data = write("xy.csv", ballbarFile(72));
  // One XY circle cannot see the Z axis's squareness errors.
  expectCleanFailure(run("identify three-axis-vertical --data " + data + " --params C0Y,A0Z -o " + output()),
                     {"refused", "A0Z has no effect on this plan"});
}

TEST_F(CliBadInput, SimulatedBallbarEvaluates) {
  const auto data = (dir_ / "sim.csv").string();
  auto r = run("simulate ballbar three-axis-vertical --centre 300,200,250 --radius 100mm --lag X=1ms -o " + data);
  ASSERT_EQ(r.exitCode, 0) << r.err;
  r = run("evaluate three-axis-vertical " + data + " -o " + output());
  EXPECT_EQ(r.exitCode, 0) << r.err;
  EXPECT_NE(r.out.find("servo mismatch"), std::string::npos);
  ASSERT_TRUE(fs::exists(output()));
  EXPECT_NE(slurp(output()).find("squareness"), std::string::npos);
}

std::string bundledStructure(const std::string& name) {
  std::ifstream in(mtacc::test::testDataDir() + "/../../data/structures/" + name + ".yaml");
  std::stringstream s;
  s << in.rdbuf();
  return s.str();
}

// Found by the bad-input corpus of issue 13: each used to write past a vector.
TEST_F(CliBadInput, SpindleNamedInAPoseIsRefused) {
  // three-axis-vertical's spindle is C: not an entry of a pose.
  const auto f = write("setat.csv", "# instrument: ballbar\n# length: 100 mm\n# set_at: X=0 mm, Y=0 mm, Z=0 mm, C=0 deg\n"
                                    "# plane: XY\nangle_deg,dL_um\n0,0\n90,0\n180,0\n270,0\n");
  expectCleanFailure(run("evaluate three-axis-vertical " + f + " -o " + output()), {f + ":3: set_at", "'C=0 deg'"});
}

TEST_F(CliBadInput, SpindleNameTakenByAnAxis) {
  const auto f = write("m.yaml", "name: x\nstructure: t-(C)-C1-Z-b-X-C-w\naxes:\n"
                                 "  X: {direction: [1, 0, 0], travel: [-400 mm, 400 mm]}\n"
                                 "  Z: {direction: [0, 0, 1], travel: [-300 mm, 300 mm]}\n"
                                 "  C: {direction: [0, 0, 1], travel: continuous}\n"
                                 "  C1: {direction: [0, 0, 1], travel: continuous}\n");
  expectCleanFailure(run("check " + f + " -o " + output()), {f + ":2: structure", "spindle's name 'C1'"});
}

TEST_F(CliBadInput, StructurePointOffItsBeam) {
  std::string text = bundledStructure("tzyx-arm-x");
  const std::string tcp = "tcp: {body: ram, point: [200 mm, 1100 mm, -100 mm]}";
  ASSERT_NE(text.find(tcp), std::string::npos);
  for (const auto& [z, reason] : {std::pair{"-1e300 mm", "out of range"}, {"-100000 mm", "not along beam 'ram'"},
                                   {"1300 mm", "not along beam 'ram'"}}) {
    SCOPED_TRACE(z);
    std::string bad = text;
    bad.replace(bad.find(tcp), tcp.size(), std::string("tcp: {body: ram, point: [200 mm, 1100 mm, ") + z + "]}");
    const auto f = write("s.yaml", bad);
    expectCleanFailure(run("dynamics modes " + f + " -o " + output()), {f + ":53: tcp.point", reason});
  }
}

// Numbers that used to overflow a conversion to int (undefined behaviour).
TEST_F(CliBadInput, HugeCountsAreOutOfRange) {
  const auto order = write("m.yaml", kMachine + "errors:\n  EXX:\n    harmonics: {terms: [{order: 1e10, amplitude: 1 um}]}\n");
  expectCleanFailure(run("check " + order + " -o " + output()), {order + ":11: errors.EXX.harmonics.terms.order", "from 1 to 1000"});
  const auto plan = write("plan.yaml", "name: p\nparameters: [C0Y]\nruns:\n  - name: c\n"
                                       "    circle: {plane: XY, centre: [0 mm, 0 mm, 100 mm], radius: 150 mm, points: 1e10}\n");
  expectCleanFailure(run("observability three-axis-vertical --plan " + plan + " -o " + output()),
                     {plan + ":5: runs[0].circle.points", "from 8 to 100000"});
}

TEST_F(CliBadInput, AxisNumberBeyondInt) {
  const auto f = write("m.yaml", "name: x\nstructure: t-(C)-Y2147483647-Z-b-X-w\naxes:\n"
                                 "  X: {direction: [1, 0, 0], travel: [-400 mm, 400 mm]}\n"
                                 "  Y2147483647: {direction: [0, 1, 0], travel: [-300 mm, 300 mm]}\n"
                                 "  Z: {direction: [0, 0, 1], travel: [-300 mm, 300 mm]}\n");
  const auto r = run("check " + f + " -o " + output());
  EXPECT_EQ(r.exitCode, 0) << r.err;
  EXPECT_NE(slurp(output()).find("Y2147483647"), std::string::npos);
}

TEST_F(CliBadInput, DirectoriesAreNotFiles) {
  const auto folder = (dir_ / "folder").string();
  fs::create_directories(folder);
  // A directory as the input file used to read as an empty file.
  expectCleanFailure(run("check " + folder + " -o " + output()), {folder + ":", "is a directory, not a file"});
  // A directory as the output file used to say "cannot move the output file into place: Success".
  const auto r = run("check three-axis-vertical -o " + folder);
  EXPECT_NE(r.exitCode, 0);
  EXPECT_NE(r.err.find("--output: '" + folder + "' is a folder; name an output file"), std::string::npos) << r.err;
  EXPECT_TRUE(fs::is_empty(folder));
}

TEST_F(CliBadInput, DuplicateAndNonScalarYamlKeys) {
  const auto twice = write("m.yaml", kMachine + "errors:\n  X0C: 10 um\n  X0C: 20 um\n");
  expectCleanFailure(run("check " + twice + " -o " + output()), {twice + ":11: errors.X0C", "key given twice"});
  const auto listKey = write("k.yaml", kMachine + "errors:\n  [X0C, Y0C]: 10 um\n");
  expectCleanFailure(run("check " + listKey + " -o " + output()), {listKey + ":10: errors", "a key must be a plain name"});
}

// Identification must not take garbage: a file given twice, a file from another machine, a pose
// beyond the travel (issue 13's cases, which used to be identified with exit 0).
TEST_F(CliBadInput, IdentificationInputsAreChecked) {
  const auto data = (dir_ / "sim.csv").string();
  auto r = run("simulate ballbar three-axis-vertical --centre 300,200,250 --radius 100mm -o " + data);
  ASSERT_EQ(r.exitCode, 0) << r.err;
  const std::string text = slurp(data);
  ASSERT_EQ(text.find("# machine: 3-axis vertical machining centre"), text.find('\n') + 1);
  expectCleanFailure(run("identify three-axis-vertical --data " + data + "," + data + " --params C0Y -o " + output()),
                     {"--data: '" + data + "' is given twice"});
  const auto other = write("other.csv", text);
  expectCleanFailure(run("identify tilting-table --data " + other + " --params C0Y -o " + output()),
                     {other + ":2: machine", "measured on '3-axis vertical machining centre, t-(C)-Z-b-Y-X-w'"});
  std::string far = text;
  const auto row = far.find("\n", far.find("angle_deg")) + 1;  // the first reading row
  far.replace(row, far.find(',', row) - row, "3100");
  const auto beyond = write("beyond.csv", far);
  expectCleanFailure(run("identify three-axis-vertical --data " + beyond + " --params C0Y -o " + output()),
                     {beyond + ":", "X=3100 mm beyond travel"});
  const auto twice = write("twice.csv", "# instrument: ballbar\n# instrument: rtest\n");
  expectCleanFailure(run("evaluate three-axis-vertical " + twice + " -o " + output()), {twice + ":2: instrument", "given twice"});
}

TEST_F(CliBadInput, MalformedStructureModels) {
  const std::string body = "bodies:\n  - {name: b, mass: 10, inertia: [1, 1, 1, 0, 0, 0]}\n";
  const auto self = write("self.yaml", body + "elements:\n  - {type: spring, bodies: [b, b], point: [0 mm, 0 mm, 0 mm], "
                                              "stiffness: 1}\ntcp: {body: b, point: [0 mm, 0 mm, 0 mm]}\n");
  expectCleanFailure(run("dynamics modes " + self + " -o " + output()), {self + ":4", "cannot join a body to itself"});
  const auto loose = write("loose.yaml", body + "elements:\n  - {type: spring, bodies: [ground, b], point: [0 mm, 0 mm, 0 mm], "
                                                "stiffness: [1, 1, 1, 0, 1, 1]}\ntcp: {body: b, point: [0 mm, 0 mm, 0 mm]}\n");
  expectCleanFailure(run("dynamics frf " + loose + " -o " + output()), {"singular", "'b' is free to move about x"});
  const auto massless = write("massless.yaml", "bodies:\n  - {name: b, inertia: [1, 1, 1, 0, 0, 0]}\nelements: []\n"
                                               "tcp: {body: b, point: [0 mm, 0 mm, 0 mm]}\n");
  expectCleanFailure(run("dynamics accel " + massless + " -o " + output()), {massless + ":2", "has no mass"});
}

// Not bad input but a doubtful result: --strict turns the warnings into exit status 4, after
// the whole result (the CSV with its correlation columns) is written.
TEST_F(CliBadInput, StrictIdentificationExitsFourOnWarnings) {
  const auto zero = write("zero.yaml", "errors: {}\n");
  ASSERT_EQ(run("simulate plan tilting-table --plan tilting-table-rtest --noise 0.5um -o " + (dir_ / "runs").string()).exitCode, 0);
  std::string data;
  for (const auto& e : fs::directory_iterator(dir_ / "runs")) data += " " + e.path().string();
  const auto r = run("identify tilting-table --errors " + zero + " --plan tilting-table-rtest --strict -o " + output() +
                     " --data" + data);
  EXPECT_EQ(r.exitCode, 4) << r.err;
  EXPECT_NE(r.err.find("mtacc: warning: the residuals are larger than the stated noise explains"), std::string::npos) << r.err;
  const auto csv = slurp(output());
  EXPECT_EQ(csv.rfind("parameter,value,standard_uncertainty,unit,r_X0B,r_Z0B,", 0), 0u) << csv.substr(0, 200);
  EXPECT_EQ(run("identify tilting-table --errors " + zero + " --plan tilting-table-rtest -o " + output() + " --data" + data).exitCode, 0);
}

}  // namespace
