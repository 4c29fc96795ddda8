#pragma once
// What the libFuzzer harnesses share: the input as text, the bundled machines they read
// against, and the front ends' handling of errors (every exception becomes a one-line message,
// so a harness only fails on a crash, a sanitizer report, a hang or unbounded memory).
#include <cstddef>
#include <cstdint>
#include <exception>
#include <memory>
#include <string>

#include "mtacc/io/machine_yaml.hpp"
#include "mtacc/kinematics/kinematic_model.hpp"

namespace mtacc::fuzz {

inline std::string text(const uint8_t* data, size_t size) { return {reinterpret_cast<const char*>(data), size}; }

inline std::shared_ptr<const Machine> bundled(const std::string& name) {
  return std::make_shared<const Machine>(loadMachine(name));
}

template <class Read>
int asTheFrontEndsDo(Read&& read) {
  try {
    read();
  } catch (const std::exception&) {
  }
  return 0;
}

}  // namespace mtacc::fuzz
