#include "mtacc/core/version.hpp"

namespace mtacc {

const char* version() { return MTACC_VERSION; }

}  // namespace mtacc
