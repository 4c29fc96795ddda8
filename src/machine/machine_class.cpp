#include "mtacc/machine/machine_class.hpp"

#include <fmt/format.h>

#include <cmath>

namespace mtacc {
namespace {

struct LinearRow {
  const char* a;
  const char* b;
  const char* name;
  const char* example;
  std::vector<std::string> errors;
};

// Table 2.2 (L345-420); F(E): a function of the position of element E.
const LinearRow kLinearClasses[] = {
    {"H", "V->H", "IA", "knee-type milling machine", {"table guide = F(table, weight/load)", "ram = F(ram)"}},
    {"V", "H->H", "IB", "fixed-bridge milling machine", {"table guide = F(table, weight/load)"}},
    {"V->H", "H", "IIA", "fixed-column milling machine",
     {"table guide = F(table, weight/load)", "column = F(ram, vertical slide)", "ram = F(ram)"}},
    {"H->V", "H", "IIB", "fixed-bridge or travelling-column machine", {"table guide = F(table, weight/load)", "column/bridge = F(ram guide)"}},
    {"H->H->V", "", "IIIA", "travelling-bridge milling machine", {"bridge guide = F(bridge)", "bridge = F(ram guide)"}},
    {"H->V->H", "", "IIIB", "travelling-column milling machine",
     {"column guide = F(column)", "column = F(vertical slide, ram)", "ram = F(ram)"}},
};

// The chain's linear axes from the bed, H or V; empty with `inclined` set when one is neither.
std::string pattern(const Machine& m, const std::vector<int>& chain, std::vector<std::string>& inclined) {
  std::string p;
  for (int i : chain) {
    const Axis& a = m.axes[static_cast<size_t>(i)];
    if (a.isRotary()) continue;
    const double along = std::abs(a.direction.dot(m.vertical));
    const char* letter = along > 1 - 1e-6 ? "V" : along < 1e-6 ? "H" : nullptr;
    if (!letter) inclined.push_back(a.name);
    p += (p.empty() ? "" : "->") + std::string(letter ? letter : "?");
  }
  return p;
}

}  // namespace

MachineClass classifyMachine(const Machine& m) {
  MachineClass c;
  std::vector<std::string> inclined;
  const std::string a = pattern(m, m.toolChain, inclined), b = pattern(m, m.workpieceChain, inclined);
  c.chains = fmt::format("A: {}, B: {}", a.empty() ? "-" : a, b.empty() ? "-" : b);
  for (const auto& name : inclined) c.notes.push_back(fmt::format("{} is neither horizontal nor vertical", name));
  for (const auto& row : kLinearClasses)
    if (a == row.a && b == row.b) {
      c.linear = row.name;
      c.example = row.example;
      c.typeDependentErrors = row.errors;
    }
  if (c.linear.empty() && inclined.empty()) c.notes.push_back(fmt::format("the linear chains ({}) match no row of Table 2.2", c.chains));
  std::vector<const Axis*> rotary;
  for (const auto& axis : m.axes)
    if (axis.isRotary() && axis.commanded()) rotary.push_back(&axis);
  if (rotary.size() != 2) {
    if (!rotary.empty()) c.notes.push_back(fmt::format("Table 2.3 classifies two rotary axes; the machine has {}", rotary.size()));
    return c;
  }
  if (std::abs(rotary[0]->direction.dot(rotary[1]->direction)) > 1e-6) {
    c.notes.push_back(fmt::format("{} and {} are not perpendicular, as Table 2.3's rotary axes are", rotary[0]->name, rotary[1]->name));
    return c;
  }
  const int onTool = (rotary[0]->side == Side::Tool) + (rotary[1]->side == Side::Tool);
  const char* descriptions[] = {
      "the workpiece table rotates about one axis and swivels about the other",
      "the workpiece table rotates, and the tool holder swivels",
      "the tool holder swivels about both axes"};
  c.rotary = onTool + 1;
  c.rotaryDescription = descriptions[onTool];
  return c;
}

}  // namespace mtacc
