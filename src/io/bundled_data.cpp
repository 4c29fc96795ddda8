#include "mtacc/io/bundled_data.hpp"

#include <algorithm>
#include <cstdlib>
#include <filesystem>
#include <vector>

#include "mtacc/core/input_error.hpp"

namespace mtacc {

std::string bundledDataDir() {
  if (const char* env = std::getenv("MTACC_DATA_DIR"); env && *env) return env;
  return MTACC_DATA_DIR;
}

std::string resolveBundled(const std::string& kind, const std::string& pathOrName) {
  namespace fs = std::filesystem;
  std::error_code ec;
  if (fs::exists(pathOrName, ec) || pathOrName.find('/') != std::string::npos || pathOrName.ends_with(".yaml"))
    return pathOrName;
  const auto folder = fs::path(bundledDataDir()) / kind;
  const auto bundled = folder / (pathOrName + ".yaml");
  if (fs::exists(bundled, ec)) return bundled.string();
  std::vector<std::string> names;
  for (const auto& entry : fs::directory_iterator(folder, ec))
    if (entry.path().extension() == ".yaml") names.push_back(entry.path().stem().string());
  std::sort(names.begin(), names.end());
  std::string list;
  for (const auto& n : names) list += (list.empty() ? "" : ", ") + n;
  const std::string what = kind == "structures" ? "model" : kind.substr(0, kind.size() - 1);
  throw InputError(InputLocation{pathOrName, 0, ""}, "neither a file nor a bundled " + what + " (bundled: " + list + ")");
}

}  // namespace mtacc
