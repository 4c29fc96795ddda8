#include "test_paths.hpp"

namespace mtacc::test {

std::string cliPath() { return MTACC_CLI; }
std::string testDataDir() { return MTACC_TEST_DATA; }

}  // namespace mtacc::test
