#pragma once
// Where the tests find the CLI they run and their data files: absolute paths of this build,
// compiled into test_paths.cpp alone (so that every other test file's object is the same for
// any checkout and build folder, and a compiler cache can share it).
#include <string>

namespace mtacc::test {

std::string cliPath();
std::string testDataDir();  // tests/data of the source tree

}  // namespace mtacc::test
