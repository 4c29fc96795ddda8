#include "mtacc/io/machine_yaml.hpp"

#include "mtacc/core/text_file.hpp"

#include <algorithm>
#include <cstdlib>
#include <filesystem>
#include <set>
#include <stdexcept>

#include "mtacc/io/bundled_data.hpp"
#include "yaml_input.hpp"

namespace mtacc {
namespace {

constexpr std::string_view kLetterOrder = "XYZUVWABC";

bool isRotaryLetter(char c) { return c == 'A' || c == 'B' || c == 'C'; }

// X, Y, Z, U, V, W, A, B, C, then by the number after the letter (X2 after X; numbers beyond 99
// keep their given order).
int canonicalRank(const std::string& name) {
  const long number = name.size() > 1 ? std::clamp(std::strtol(name.c_str() + 1, nullptr, 10), 0L, 99L) : 0L;
  return static_cast<int>(kLetterOrder.find(name[0])) * 100 + static_cast<int>(number);
}

Axis readAxis(const yamlin::Context& ctx, const std::string& name, Side side, const YAML::Node& node) {
  const std::string path = "axes." + name;
  yamlin::rejectUnknownKeys(ctx, node, path, {"type", "direction", "location", "offset", "travel", "error_frame"});
  Axis axis;
  axis.name = name;
  axis.side = side;
  axis.line = node.Mark().line + 1;
  axis.type = isRotaryLetter(name[0]) ? AxisType::Rotary : AxisType::Linear;
  if (node["type"]) {
    const auto t = yamlin::scalar(ctx, node["type"], path + ".type");
    if (t == "linear") axis.type = AxisType::Linear;
    else if (t == "rotary") axis.type = AxisType::Rotary;
    else ctx.fail(node["type"], path + ".type", "expected 'linear' or 'rotary', got '" + t + "'");
  }
  if (!node["direction"]) ctx.fail(node, path + ".direction", "missing direction vector");
  axis.direction = yamlin::unitVector(ctx, node["direction"], path + ".direction");
  if (node["location"]) {
    if (axis.type != AxisType::Rotary) ctx.fail(node["location"], path + ".location", "only rotary axes have a location");
    axis.location = yamlin::lengthVector(ctx, node["location"], path + ".location");
  }
  if (node["offset"]) axis.offset = yamlin::lengthVector(ctx, node["offset"], path + ".offset");
  axis.errorFrame = axis.type == AxisType::Rotary ? ErrorFrame::Fixed : ErrorFrame::Moving;
  if (node["error_frame"]) {
    const auto f = yamlin::scalar(ctx, node["error_frame"], path + ".error_frame");
    if (f == "moving") axis.errorFrame = ErrorFrame::Moving;
    else if (f == "fixed") axis.errorFrame = ErrorFrame::Fixed;
    else ctx.fail(node["error_frame"], path + ".error_frame", "expected 'moving' or 'fixed', got '" + f + "'");
  }
  const auto travel = node["travel"];
  if (!travel) ctx.fail(node, path + ".travel", "missing travel ([min, max] with units, or 'continuous' for a rotary axis)");
  if (travel.IsScalar() && travel.Scalar() == "continuous") {
    if (axis.type != AxisType::Rotary) ctx.fail(travel, path + ".travel", "only a rotary axis can be continuous");
  } else {
    if (!travel.IsSequence() || travel.size() != 2) ctx.fail(travel, path + ".travel", "expected [min, max]");
    const Dimension dim = axis.type == AxisType::Rotary ? Dimension::Angle : Dimension::Length;
    const double lo = yamlin::quantity(ctx, travel[0], path + ".travel", dim);
    const double hi = yamlin::quantity(ctx, travel[1], path + ".travel", dim);
    if (!(lo < hi)) ctx.fail(travel, path + ".travel", "min must be smaller than max");
    axis.travel = Travel{lo, hi};
  }
  return axis;
}

}  // namespace

Machine loadMachine(const std::string& pathOrName) {
  const auto path = resolveBundled("machines", pathOrName);
  return parseMachine(readTextFile(path), path);
}

Machine parseMachine(const std::string& yamlText, const std::string& sourceName) {
  const yamlin::Context ctx{sourceName};
  const auto root = yamlin::loadText(yamlText, sourceName);
  if (!root.IsMap()) ctx.fail(root, "", "a machine file must be a YAML mapping");
  yamlin::rejectUnknownKeys(ctx, root, "", {"name", "structure", "axes", "spindle", "tool", "workpiece", "vertical", "errors", "workpiece_load", "description", "source"});

  Machine m;
  m.sourceFile = sourceName;
  if (root["vertical"]) m.vertical = yamlin::unitVector(ctx, root["vertical"], "vertical");
  m.name = yamlin::scalar(ctx, root["name"], "name");
  const auto structureNode = root["structure"];
  try {
    m.structure = parseStructureCode(yamlin::scalar(ctx, structureNode, "structure"));
  } catch (const InvalidInput& e) {
    ctx.fail(structureNode, "structure", e.what());
  }

  const auto axesNode = root["axes"];
  if (!axesNode || !axesNode.IsMap()) ctx.fail(root, "axes", "missing 'axes' mapping");
  std::set<std::string> inCode(m.structure.toolChain.begin(), m.structure.toolChain.end());
  inCode.insert(m.structure.workpieceChain.begin(), m.structure.workpieceChain.end());
  for (const auto& kv : axesNode) {
    const auto name = kv.first.as<std::string>();
    if (!inCode.count(name))
      ctx.fail(kv.first, "axes." + name, "axis '" + name + "' is not in the structure code " + m.structure.text);
  }
  auto addChain = [&](const std::vector<std::string>& names, Side side) {
    for (const auto& name : names) {
      const auto node = axesNode[name];
      if (!node) ctx.fail(axesNode, "axes." + name, "axis '" + name + "' of the structure code has no entry");
      m.axes.push_back(readAxis(ctx, name, side, node));
    }
  };
  addChain(m.structure.toolChain, Side::Tool);
  addChain(m.structure.workpieceChain, Side::Workpiece);
  std::stable_sort(m.axes.begin(), m.axes.end(),
                   [](const Axis& a, const Axis& b) { return canonicalRank(a.name) < canonicalRank(b.name); });

  const auto toolNode = root["tool"];
  if (toolNode) {
    yamlin::rejectUnknownKeys(ctx, toolNode, "tool", {"offset", "direction"});
    if (toolNode["offset"]) m.toolOffset = yamlin::lengthVector(ctx, toolNode["offset"], "tool.offset");
    if (toolNode["direction"]) m.toolDirection = yamlin::unitVector(ctx, toolNode["direction"], "tool.direction");
  }
  if (m.structure.spindle) {
    Axis spindle;
    spindle.name = *m.structure.spindle;
    if (spindle.name.find_first_of("ABC") != 0)
      ctx.fail(structureNode, "structure", "the spindle turns: name it after the axis it turns about (A, B or C), not '" +
                                               spindle.name + "'");
    if (inCode.count(spindle.name)) spindle.name += "1";  // t-(C)-...-C-w: the spindle becomes C1
    if (inCode.count(spindle.name))
      ctx.fail(structureNode, "structure", "the spindle's name '" + spindle.name + "' is already the name of an axis");
    spindle.type = AxisType::Spindle;
    spindle.side = Side::Tool;
    spindle.direction = m.toolDirection;
    spindle.location = m.toolOffset;
    spindle.errorFrame = ErrorFrame::Fixed;
    const auto spindleNode = root["spindle"];
    if (spindleNode) {
      yamlin::rejectUnknownKeys(ctx, spindleNode, "spindle", {"location"});
      if (spindleNode["location"]) spindle.location = yamlin::lengthVector(ctx, spindleNode["location"], "spindle.location");
      spindle.line = spindleNode.Mark().line + 1;
    }
    m.axes.push_back(spindle);
  } else if (root["spindle"]) {
    ctx.fail(root["spindle"], "spindle", "the structure code names no spindle '(...)'");
  }

  for (const auto& name : m.structure.toolChain) m.toolChain.push_back(m.axisIndex(name));
  if (m.structure.spindle) m.toolChain.push_back(static_cast<int>(m.axes.size()) - 1);
  for (const auto& name : m.structure.workpieceChain) m.workpieceChain.push_back(m.axisIndex(name));

  m.referencePose.assign(static_cast<size_t>(m.commandedCount()), 0.0);
  const auto wpNode = root["workpiece"];
  if (wpNode) {
    yamlin::rejectUnknownKeys(ctx, wpNode, "workpiece", {"offset", "alignment", "reference_pose"});
    if (wpNode["offset"]) m.workpieceOffset = yamlin::lengthVector(ctx, wpNode["offset"], "workpiece.offset");
    if (wpNode["alignment"]) {
      const auto a = yamlin::scalar(ctx, wpNode["alignment"], "workpiece.alignment");
      if (a == "table") m.alignment = WorkpieceAlignment::Table;
      else if (a == "machine") m.alignment = WorkpieceAlignment::Machine;
      else ctx.fail(wpNode["alignment"], "workpiece.alignment", "expected 'table' or 'machine', got '" + a + "'");
    }
    if (const auto ref = wpNode["reference_pose"]) {
      if (!ref.IsMap()) ctx.fail(ref, "workpiece.reference_pose", "expected a mapping axis: position");
      for (const auto& kv : ref) {
        const auto name = kv.first.as<std::string>();
        const int i = m.commandedAxisIndex(name);
        if (i < 0) ctx.fail(kv.first, "workpiece.reference_pose." + name, "unknown axis '" + name + "'");
        m.referencePose[i] = yamlin::quantity(ctx, kv.second, "workpiece.reference_pose." + name,
                                              m.axes[i].isRotary() ? Dimension::Angle : Dimension::Length);
      }
      if (const auto violation = m.travelViolation(m.referencePose); !violation.empty())
        ctx.fail(ref, "workpiece.reference_pose", "the pose " + violation);
    }
  }
  return m;
}

}  // namespace mtacc
