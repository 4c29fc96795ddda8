#pragma once
// A cubic machining test (YAML, docs/file-formats.md "Cubic machining tests"): block, zones
// with their tool vectors, tool, pick, depth and feed. Bundled tests live in
// data/test-pieces/ (seed001-cubic: the test of seed 001).
#include <string>

#include "mtacc/procedures/cubic_test.hpp"

namespace mtacc {

// By path, or by the name of a bundled test. Throws InputError naming file, line and key.
CubicTestSpec loadCubicTest(const std::string& pathOrName);
CubicTestSpec parseCubicTest(const std::string& text, const std::string& sourceName);

}  // namespace mtacc
