#pragma once
// ISO 230-2 test data (docs/file-formats.md "Positioning tests"), in either of two forms, told
// apart by their content:
//  * the KEY=value form of the ecmc ISO 230-2 tools: UNIT, CYCLES, POSITIONS, TGT_DATA[i],
//    REF_DATA_FWD[i,j] and REF_DATA_BWD[i,j] (measured positions), '#' comments;
//  * a CSV `target,cycle,forward,backward` with '# unit:' (required), '# values: positions' (the
//    default) or 'deviations', and an optional '# name:'.
// The unit decides the axis kind: a length for a linear axis, an angle for a rotary one.
#include <string>

#include "mtacc/procedures/iso230_2.hpp"

namespace mtacc {

// Throws InputError naming file, line and key: unknown or repeated keys, indices out of range,
// a missing target or reading, ragged cycles, a value that is not finite, deviations beyond
// ±10 mm or ±10°, fewer than 2 targets or cycles.
PositioningTest readPositioningTest(const std::string& path);
PositioningTest parsePositioningTest(const std::string& text, const std::string& sourceName);

}  // namespace mtacc
