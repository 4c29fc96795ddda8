#pragma once
// Seed 003's classification of machines (BCR report 1991, ch. 2, Tables 2.2 and 2.3): the
// linear axes of the tool chain (A) and of the workpiece chain (B), each horizontal (H) or
// vertical (V) against the machine's vertical, in their order from the bed, give the class of
// the basic machine and the bendings to expect while it traverses; the sides of its two
// perpendicular rotary axes give the rotary class.
#include <string>
#include <vector>

#include "mtacc/machine/machine.hpp"

namespace mtacc {

struct MachineClass {
  std::string chains;   // "A: H->V, B: H"
  std::string linear;   // "IA" ... "IIIB"; empty when no row of Table 2.2 fits
  std::string example;  // Table 2.2's example machine, "knee-type milling machine"
  std::vector<std::string> typeDependentErrors;  // "table guide = F(table, weight/load)"
  int rotary = 0;       // Table 2.3's class 1, 2 or 3; 0 when none applies
  std::string rotaryDescription;
  std::vector<std::string> notes;  // why a class is missing
};

MachineClass classifyMachine(const Machine& machine);

}  // namespace mtacc
