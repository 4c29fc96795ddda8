#pragma once
// The data bundled with mtacc (machines, plans, structures, limits): found in the folder named
// by the environment variable MTACC_DATA_DIR when set (the installed Python package sets it to
// its own copy), else in the source tree's data/.
#include <string>

namespace mtacc {

std::string bundledDataDir();

// A path as given when it names an existing file; else, for a bare name without '/', the
// bundled file <data>/<kind>/<name>.yaml when it exists; else the argument (whose reading then
// fails with its name).
std::string resolveBundled(const std::string& kind, const std::string& pathOrName);

}  // namespace mtacc
