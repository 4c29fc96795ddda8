#pragma once
// The one exception type for bad input: it names where the problem is (file, line, key)
// so that every front end can print a single line and exit non-zero.
#include <stdexcept>
#include <string>

namespace mtacc {

struct InputLocation {
  std::string file;  // empty when the input did not come from a file
  int line = 0;      // 1-based; 0 when unknown
  std::string key;   // dotted path of the offending key, or a pose description
};

class InputError : public std::runtime_error {
 public:
  InputError(InputLocation where, const std::string& what);
  const InputLocation& where() const { return where_; }
  const std::string& reason() const { return reason_; }

 private:
  InputLocation where_;
  std::string reason_;
};

// Bad input found by domain code, which cannot name the file or key it came from: the workflow
// that called it catches it to add them, and a front end that receives it unlocated still
// reports it as any InputError (exit code 2, mtacc.InputError in Python).
class InvalidInput : public InputError {
 public:
  explicit InvalidInput(const std::string& what) : InputError({}, what) {}
};

// Input that is well formed but asks for a pose the machine cannot reach (a TCP or a tool
// direction out of its reach): the CLI reports it as any InputError, Python raises
// UnreachablePose (itself an InputError there).
class UnreachableInput : public InputError {
 public:
  using InputError::InputError;
};

// Raised when a requested pose cannot be reached (direction impossible, beyond travel,
// singular without a rule to resolve it).
class UnreachablePose : public std::runtime_error {
 public:
  using std::runtime_error::runtime_error;
};

}  // namespace mtacc
