#include "mtacc/core/input_error.hpp"

#include <fmt/format.h>

namespace mtacc {
namespace {
std::string describe(const InputLocation& where, const std::string& what) {
  std::string prefix;
  if (!where.file.empty()) prefix = where.file;
  if (where.line > 0) prefix += fmt::format(":{}", where.line);
  if (!where.key.empty()) prefix += (prefix.empty() ? "" : ": ") + where.key;
  return prefix.empty() ? what : prefix + ": " + what;
}
}  // namespace

InputError::InputError(InputLocation where, const std::string& what)
    : std::runtime_error(describe(where, what)), where_(std::move(where)), reason_(what) {}

}  // namespace mtacc
