#include "mtacc/io/structure_yaml.hpp"

#include "mtacc/core/text_file.hpp"

#include <functional>

#include <Eigen/Eigenvalues>
#include <fmt/format.h>

#include "mtacc/core/units.hpp"
#include "mtacc/io/bundled_data.hpp"
#include "yaml_input.hpp"

namespace mtacc {
namespace {

using yamlin::Context;
constexpr double kMicrometre = 1e-6;  // m
// The SI numbers of a structure (masses, moduli, section constants, stiffness, damping) lie
// far below this; a larger one is a unit mistake and would overflow the assembled matrices.
constexpr double kLargestSiNumber = 1e15;

double positive(const Context& ctx, const YAML::Node& node, const std::string& key) {
  const double v = yamlin::number(ctx, node, key);
  if (!(v > 0 && v <= kLargestSiNumber)) ctx.fail(node, key, "must be positive and at most 1e15 (SI units)");
  return v;
}

double positiveLength(const Context& ctx, const YAML::Node& node, const std::string& key) {
  const double v = yamlin::quantity(ctx, node, key, Dimension::Length);
  if (!(v > 0)) ctx.fail(node, key, "must be positive");
  return v;
}

// [a, b, c] or a single number repeated n times.
std::vector<double> numbers(const Context& ctx, const YAML::Node& node, const std::string& key, size_t n) {
  std::vector<double> out;
  if (node && node.IsScalar()) {
    out.assign(n, yamlin::number(ctx, node, key));
  } else {
    if (!node || !node.IsSequence() || node.size() != n)
      ctx.fail(node, key, "expected " + std::to_string(n) + " numbers");
    for (size_t i = 0; i < n; ++i) out.push_back(yamlin::number(ctx, node[i], key));
  }
  for (double v : out)
    if (!(v >= 0 && v <= kLargestSiNumber)) ctx.fail(node, key, "must be from 0 to 1e15 (SI units)");
  return out;
}

// Local frame: x along `along`, z towards `up` (default: the global axis least aligned with x).
Mat3 frameFrom(const Context& ctx, const YAML::Node& e, const std::string& key) {
  if (!e["along"]) return Mat3::Identity();
  const Vec3 x = yamlin::unitVector(ctx, e["along"], key + ".along");
  Vec3 up;
  if (e["up"]) {
    up = yamlin::unitVector(ctx, e["up"], key + ".up");
  } else {
    Eigen::Index k = 0;
    x.cwiseAbs().minCoeff(&k);
    up = Vec3::Unit(k);
  }
  Vec3 y = up.cross(x);
  if (y.norm() < 1e-9) ctx.fail(e["up"], key + ".up", "must not be parallel to 'along'");
  y.normalize();
  Mat3 r;
  r << x, y, x.cross(y);
  return r;
}

BodyPart readPart(const Context& ctx, const YAML::Node& p, const std::string& key) {
  yamlin::rejectUnknownKeys(ctx, p, key, {"cuboid", "cylinder", "prism", "centre", "mass", "density"});
  const Vec3 centre = p["centre"] ? Vec3(yamlin::lengthVector(ctx, p["centre"], key + ".centre") * 1e-3) : Vec3::Zero();
  double volume = 0;
  std::function<BodyPart(double)> make;
  if (p["cuboid"]) {
    const Vec3 s = yamlin::lengthVector(ctx, p["cuboid"], key + ".cuboid") * 1e-3;
    if ((s.array() <= 0).any()) ctx.fail(p["cuboid"], key + ".cuboid", "dimensions must be positive");
    volume = s.prod();
    make = [s, centre](double m) { return cuboidPart(s, m, centre); };
  } else if (const auto c = p["cylinder"]) {
    yamlin::rejectUnknownKeys(ctx, c, key + ".cylinder", {"radius", "inner_radius", "length", "axis"});
    const double r = yamlin::quantity(ctx, c["radius"], key + ".cylinder.radius", Dimension::Length) * 1e-3;
    const double ri = c["inner_radius"] ? yamlin::quantity(ctx, c["inner_radius"], key + ".cylinder.inner_radius", Dimension::Length) * 1e-3 : 0.0;
    const double l = yamlin::quantity(ctx, c["length"], key + ".cylinder.length", Dimension::Length) * 1e-3;
    const std::string axis = c["axis"] ? yamlin::scalar(ctx, c["axis"], key + ".cylinder.axis") : "z";
    if (axis != "x" && axis != "y" && axis != "z") ctx.fail(c["axis"], key + ".cylinder.axis", "expected x, y or z");
    if (!(r > ri && ri >= 0 && l > 0)) ctx.fail(c, key + ".cylinder", "needs radius > inner_radius >= 0 and length > 0");
    volume = kPi * (r * r - ri * ri) * l;
    const int a = axis[0] - 'x';
    make = [shape = CylinderShape{r, ri, l, a}, centre](double m) { return cylinderPart(shape, m, centre); };
  } else if (p["prism"]) {
    const Vec3 s = yamlin::lengthVector(ctx, p["prism"], key + ".prism") * 1e-3;
    if ((s.array() <= 0).any()) ctx.fail(p["prism"], key + ".prism", "dimensions must be positive");
    volume = 0.5 * s.prod();
    make = [s, centre](double m) { return prismPart(s, m, centre); };
  } else {
    ctx.fail(p, key, "expected cuboid, cylinder or prism");
  }
  double mass = 0;
  if (p["mass"]) mass = positive(ctx, p["mass"], key + ".mass");
  else if (p["density"]) mass = positive(ctx, p["density"], key + ".density") * volume;
  else ctx.fail(p, key, "a part needs its mass (kg) or density (kg/m^3)");
  return make(mass);
}

RigidBody readBody(const Context& ctx, const YAML::Node& b, const std::string& key) {
  yamlin::rejectUnknownKeys(ctx, b, key, {"name", "mass", "centre", "inertia", "parts", "size"});
  const std::string name = yamlin::scalar(ctx, b["name"], key + ".name");
  RigidBody body;
  if (b["parts"]) {
    if (!b["parts"].IsSequence() || b["parts"].size() == 0) ctx.fail(b["parts"], key + ".parts", "expected a list of parts");
    std::vector<BodyPart> parts;
    for (size_t i = 0; i < b["parts"].size(); ++i)
      parts.push_back(readPart(ctx, b["parts"][i], key + ".parts[" + std::to_string(i) + "]"));
    body = combineParts(name, parts);
  } else {
    if (!b["mass"]) ctx.fail(b, key + ".mass", "body '" + name + "' has no mass (give mass, centre, inertia or parts)");
    body.name = name;
    body.mass = positive(ctx, b["mass"], key + ".mass");
    body.centre = b["centre"] ? Vec3(yamlin::lengthVector(ctx, b["centre"], key + ".centre") * 1e-3) : Vec3::Zero();
    const auto j = numbers(ctx, b["inertia"], key + ".inertia", 6);  // Jxx Jyy Jzz Jxy Jxz Jyz, kg m^2
    body.inertia << j[0], j[3], j[4], j[3], j[1], j[5], j[4], j[5], j[2];
    Eigen::SelfAdjointEigenSolver<Mat3> eig(body.inertia);
    if (eig.eigenvalues().minCoeff() <= 0)
      ctx.fail(b["inertia"], key + ".inertia", "the inertia tensor of '" + name + "' must be positive definite");
  }
  if (!b["parts"]) body.boxCentre = body.centre;
  if (b["size"]) body.size = yamlin::lengthVector(ctx, b["size"], key + ".size") * 1e-3;
  body.line = b.Mark().line + 1;
  return body;
}

// A flexible beam: its geometry and section as written (see addBeam for the model).
void readBeam(const Context& ctx, const YAML::Node& b, const std::string& key, StructureModel& m) {
  yamlin::rejectUnknownKeys(ctx, b, key, {"name", "from", "to", "section", "mass_per_length", "E", "G", "A", "I", "It",
                                          "up", "stiffness_damping"});
  BeamSpec beam;
  beam.name = yamlin::scalar(ctx, b["name"], key + ".name");
  beam.from = yamlin::lengthVector(ctx, b["from"], key + ".from") * 1e-3;
  beam.to = yamlin::lengthVector(ctx, b["to"], key + ".to") * 1e-3;
  if ((beam.to - beam.from).norm() <= 0) ctx.fail(b["to"], key + ".to", "the beam has no length");
  if (!b["section"] || !b["section"].IsSequence() || b["section"].size() != 2)
    ctx.fail(b, key + ".section", "expected [width, height] of the cross-section, e.g. [400 mm, 400 mm]");
  beam.section = {positiveLength(ctx, b["section"][0], key + ".section") * 1e-3,
                  positiveLength(ctx, b["section"][1], key + ".section") * 1e-3};
  beam.massPerLength = positive(ctx, b["mass_per_length"], key + ".mass_per_length");
  beam.youngsModulus = positive(ctx, b["E"], key + ".E");
  beam.shearModulus = positive(ctx, b["G"], key + ".G");
  beam.area = positive(ctx, b["A"], key + ".A");
  beam.torsionConstant = positive(ctx, b["It"], key + ".It");
  const auto inertia = numbers(ctx, b["I"], key + ".I", 2);
  beam.areaMoments = {inertia[0], inertia[1]};
  if (b["stiffness_damping"]) {
    beam.stiffnessDamping = yamlin::number(ctx, b["stiffness_damping"], key + ".stiffness_damping");
    if (!(beam.stiffnessDamping >= 0 && beam.stiffnessDamping <= 1))
      ctx.fail(b["stiffness_damping"], key + ".stiffness_damping", "must be from 0 to 1 s");
  }
  if (b["up"]) beam.up = yamlin::unitVector(ctx, b["up"], key + ".up");
  addBeam(m, beam, b.Mark().line + 1);
}

int bodyRef(const Context& ctx, const StructureModel& m, const YAML::Node& node, const std::string& key) {
  const std::string name = yamlin::scalar(ctx, node, key);
  const int i = m.bodyIndex(name);
  if (i == -2) ctx.fail(node, key, "unknown body '" + name + "' (or 'ground')");
  return i;
}

int beamRef(const StructureModel& m, const std::string& name) {
  for (size_t i = 0; i < m.beams.size(); ++i)
    if (m.beams[i].name == name) return static_cast<int>(i);
  return -1;
}

Connection readConnection(const Context& ctx, const StructureModel& m, const YAML::Node& e, const std::string& key) {
  yamlin::rejectUnknownKeys(ctx, e, key,
                            {"name", "type", "bodies", "point", "along", "up", "stiffness", "damping", "kv", "kp", "moves_with"});
  Connection c;
  c.type = yamlin::scalar(ctx, e["type"], key + ".type");
  c.name = e["name"] ? yamlin::scalar(ctx, e["name"], key + ".name") : c.type + "-" + key;
  if (!e["bodies"] || !e["bodies"].IsSequence() || e["bodies"].size() != 2)
    ctx.fail(e, key + ".bodies", "expected [body a, body b] (b carries the point)");
  for (int side = 0; side < 2; ++side) {
    const auto node = e["bodies"][static_cast<size_t>(side)];
    const int beam = beamRef(m, yamlin::scalar(ctx, node, key + ".bodies"));
    const int body = beam >= 0 ? m.beams[static_cast<size_t>(beam)].first : bodyRef(ctx, m, node, key + ".bodies");
    (side == 0 ? c.a : c.b) = body;
    (side == 0 ? c.beamA : c.beamB) = beam;
  }
  if (c.a == c.b && c.beamA == c.beamB) ctx.fail(e["bodies"], key + ".bodies", "an element cannot join a body to itself");
  if (e["moves_with"]) {
    const std::string w = yamlin::scalar(ctx, e["moves_with"], key + ".moves_with");
    if (w != "a" && w != "b") ctx.fail(e["moves_with"], key + ".moves_with", "expected a or b");
    c.followsA = w == "a";
  }
  c.point = yamlin::lengthVector(ctx, e["point"], key + ".point") * 1e-3;
  c.frame = frameFrom(ctx, e, key);
  c.line = e.Mark().line + 1;
  // Stiffness in N/um (translation) and N m/urad (rotation); damping in N s/m and N m s/rad.
  if (c.type == "guide") {
    const auto k = numbers(ctx, e["stiffness"], key + ".stiffness", 2);
    c.stiffness << 0, k[0] / kMicrometre, k[1] / kMicrometre, 0, 0, 0;
    if (e["damping"]) {
      const auto d = numbers(ctx, e["damping"], key + ".damping", 2);
      c.damping << 0, d[0], d[1], 0, 0, 0;
    }
  } else if (c.type == "drive") {
    c.stiffness[0] = numbers(ctx, e["stiffness"], key + ".stiffness", 1)[0] / kMicrometre;
    if (e["damping"]) c.damping[0] = numbers(ctx, e["damping"], key + ".damping", 1)[0];
  } else if (c.type == "direct_drive") {
    // Cascaded P position loop (kv, 1/s) and P velocity loop (kp, N s/m): k = kv kp, d = kp.
    const double kv = positive(ctx, e["kv"], key + ".kv"), kp = positive(ctx, e["kp"], key + ".kp");
    c.stiffness[0] = kv * kp;
    c.damping[0] = kp;
  } else if (c.type == "setup" || c.type == "bearing" || c.type == "spring") {
    const auto k = numbers(ctx, e["stiffness"], key + ".stiffness", 6);
    for (int i = 0; i < 6; ++i) c.stiffness[i] = k[static_cast<size_t>(i)] / kMicrometre;
    if (e["damping"]) {
      const auto d = numbers(ctx, e["damping"], key + ".damping", 6);
      for (int i = 0; i < 6; ++i) c.damping[i] = d[static_cast<size_t>(i)];
    }
  } else {
    ctx.fail(e["type"], key + ".type", "unknown element type '" + c.type + "' (guide, drive, direct_drive, bearing, setup, spring)");
  }
  return c;
}

}  // namespace

StructureModel parseStructure(const std::string& text, const std::string& source) {
  const Context ctx{source};
  const auto root = yamlin::loadText(text, source);
  if (!root.IsMap()) ctx.fail(root, "", "expected a mapping with bodies, elements, axes, tcp");
  yamlin::rejectUnknownKeys(ctx, root, "", {"name", "description", "bodies", "beams", "elements", "axes", "tcp", "workpiece"});
  StructureModel m;
  m.name = root["name"] ? yamlin::scalar(ctx, root["name"], "name") : source;
  m.sourceFile = source;
  if (!root["bodies"] || !root["bodies"].IsSequence()) ctx.fail(root, "bodies", "expected a list of bodies");
  for (size_t i = 0; i < root["bodies"].size(); ++i) {
    auto body = readBody(ctx, root["bodies"][i], "bodies[" + std::to_string(i) + "]");
    if (m.bodyIndex(body.name) != -2) ctx.fail(root["bodies"][i], "bodies[" + std::to_string(i) + "].name", "duplicate body '" + body.name + "'");
    m.bodies.push_back(body);
  }
  if (const auto beams = root["beams"])
    for (size_t i = 0; i < beams.size(); ++i) readBeam(ctx, beams[i], "beams[" + std::to_string(i) + "]", m);
  if (!root["elements"] || !root["elements"].IsSequence()) ctx.fail(root, "elements", "expected a list of connecting elements");
  for (size_t i = 0; i < root["elements"].size(); ++i)
    m.connections.push_back(readConnection(ctx, m, root["elements"][i], "elements[" + std::to_string(i) + "]"));
  if (const auto axes = root["axes"]) {
    for (size_t i = 0; i < axes.size(); ++i) {
      const auto a = axes[i];
      const std::string key = "axes[" + std::to_string(i) + "]";
      yamlin::rejectUnknownKeys(ctx, a, key, {"name", "direction", "moves", "travel"});
      StructureAxis axis;
      axis.name = yamlin::scalar(ctx, a["name"], key + ".name");
      axis.direction = yamlin::unitVector(ctx, a["direction"], key + ".direction");
      if (!a["moves"] || !a["moves"].IsSequence()) ctx.fail(a, key + ".moves", "expected the list of bodies the axis carries");
      for (const auto& n : a["moves"]) {
        const std::string name = yamlin::scalar(ctx, n, key + ".moves");
        bool found = false;
        for (size_t k = 0; k < m.bodies.size(); ++k)
          if (m.bodies[k].name == name || m.bodies[k].name.rfind(name + ".", 0) == 0) {  // a beam: all its segments
            axis.moves.push_back(static_cast<int>(k));
            found = true;
          }
        if (!found) ctx.fail(n, key + ".moves", "unknown body '" + name + "'");
      }
      if (a["travel"]) {
        if (!a["travel"].IsSequence() || a["travel"].size() != 2) ctx.fail(a["travel"], key + ".travel", "expected [min, max]");
        axis.min = yamlin::quantity(ctx, a["travel"][0], key + ".travel", Dimension::Length) * 1e-3;
        axis.max = yamlin::quantity(ctx, a["travel"][1], key + ".travel", Dimension::Length) * 1e-3;
        if (!(axis.min < axis.max)) ctx.fail(a["travel"], key + ".travel", "min must be smaller than max");
      }
      m.axes.push_back(axis);
    }
  }
  // A point on a beam belongs to the segment it lies in.
  auto pointBody = [&](const YAML::Node& node, const std::string& key, Vec3& point) {
    point = yamlin::lengthVector(ctx, node["point"], key + ".point") * 1e-3;
    const int beam = beamRef(m, yamlin::scalar(ctx, node["body"], key + ".body"));
    if (beam < 0) return bodyRef(ctx, m, node["body"], key + ".body");
    const auto& b = m.beams[static_cast<size_t>(beam)];
    const double s = (point - b.from).dot(b.axis) / b.length;
    if (!(s >= -1e-9 && s <= 1 + 1e-9))
      ctx.fail(node["point"], key + ".point",
               fmt::format("the point is not along beam '{}': it lies {:.4g} mm from its start, the beam is {:.4g} mm long",
                           b.name, s * b.length * 1e3, b.length * 1e3));
    return b.segmentAt(s);
  };
  if (!root["tcp"]) ctx.fail(root, "tcp", "missing tcp: {body, point}");
  m.tcpBody = pointBody(root["tcp"], "tcp", m.tcpPoint);
  if (const auto w = root["workpiece"]) m.workpieceBody = pointBody(w, "workpiece", m.workpiecePoint);
  if (m.tcpBody == m.workpieceBody) ctx.fail(root["tcp"], "tcp.body", "the TCP and the workpiece point are on the same body");
  return m;
}

StructureModel loadStructure(const std::string& pathOrName) {
  const std::string path = resolveBundled("structures", pathOrName);
  return parseStructure(readTextFile(path), path);
}

}  // namespace mtacc
