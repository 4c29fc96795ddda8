#include "mtacc/io/bundled_data.hpp"

#include <cstdlib>
#include <filesystem>

namespace mtacc {

std::string bundledDataDir() {
  if (const char* env = std::getenv("MTACC_DATA_DIR"); env && *env) return env;
  return MTACC_DATA_DIR;
}

std::string resolveBundled(const std::string& kind, const std::string& pathOrName) {
  namespace fs = std::filesystem;
  if (fs::exists(pathOrName) || pathOrName.find('/') != std::string::npos) return pathOrName;
  const auto bundled = fs::path(bundledDataDir()) / kind / (pathOrName + ".yaml");
  return fs::exists(bundled) ? bundled.string() : pathOrName;
}

}  // namespace mtacc
