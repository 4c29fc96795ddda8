#include "cli_common.hpp"

#include <unistd.h>

#include <cstdlib>
#include <stdexcept>

namespace mtacc::cli {

void runPythonModule(const std::string& module, const std::vector<std::string>& arguments) {
  const char* old = std::getenv("PYTHONPATH");
  std::string path = MTACC_PYTHON_DIR;
  if (old && *old) path.append(":").append(old);
  ::setenv("PYTHONPATH", path.c_str(), 1);
  std::vector<std::string> args{"/usr/bin/python3", "-m", module};
  args.insert(args.end(), arguments.begin(), arguments.end());
  std::vector<char*> argv;
  for (auto& a : args) argv.push_back(a.data());
  argv.push_back(nullptr);
  ::execv(argv[0], argv.data());
  throw std::runtime_error("cannot start /usr/bin/python3 -m " + module);
}

}  // namespace mtacc::cli
