#include "mtacc/io/text_file.hpp"

#include <fmt/format.h>

#include <unistd.h>

#include <cstdio>
#include <filesystem>
#include <fstream>
#include <sstream>

#include "mtacc/core/input_error.hpp"

namespace mtacc {

std::string readTextFile(const std::string& path) {
  namespace fs = std::filesystem;
  std::error_code ec;
  const auto status = fs::status(path, ec);
  if (!fs::exists(status)) throw InputError(InputLocation{path, 0, ""}, "no such file");
  if (fs::is_directory(status)) throw InputError(InputLocation{path, 0, ""}, "is a directory, not a file");
  std::ifstream in(path, std::ios::binary);
  if (!in) throw InputError(InputLocation{path, 0, ""}, "cannot open file");
  std::stringstream buffer;
  buffer << in.rdbuf();
  return buffer.str();
}

void writeFileAtomically(const std::string& path, const std::string& content, const std::string& key) {
  namespace fs = std::filesystem;
  const fs::path target(path);
  if (fs::is_directory(target)) throw InputError(InputLocation{"", 0, key}, "'" + path + "' is a folder; name an output file");
  const fs::path dir = target.has_parent_path() ? target.parent_path() : fs::path(".");
  const fs::path tmp = dir / fmt::format(".{}.tmp{}", target.filename().string(), ::getpid());
  {
    std::ofstream out(tmp, std::ios::binary | std::ios::trunc);
    if (!out) throw InputError(InputLocation{"", 0, key}, "cannot write '" + path + "' (does its folder exist?)");
    out << content;
    out.flush();
    if (!out) {
      std::error_code ec;
      fs::remove(tmp, ec);
      throw InputError(InputLocation{"", 0, key}, "writing '" + path + "' failed (is the disk full?)");
    }
  }
  std::error_code ec;
  fs::rename(tmp, target, ec);
  if (ec) {
    fs::remove(tmp, ec);
    throw InputError(InputLocation{"", 0, key}, "cannot move '" + path + "' into place: " + ec.message());
  }
}

}  // namespace mtacc
