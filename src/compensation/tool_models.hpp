#pragma once
// The machine and its errors compiled once per tool length a program uses (G43 H<n>). Private
// to the compensation module.
#include <map>
#include <memory>
#include <utility>

#include "mtacc/errors/error_model.hpp"
#include "mtacc/kinematics/kinematic_model.hpp"

namespace mtacc {

struct Models {
  KinematicModel actual, nominal;
};

// The machine with the tool of the given length (mm beyond the machine file's TCP, along the tool).
// The machine and its errors with the tool of each length met, compiled once.
class ToolModels {
 public:
  ToolModels(const std::shared_ptr<const Machine>& machine, const ErrorModel& errors) : machine_(machine), errors_(errors) {}
  const Models& operator()(double toolLength) {
    if (last_ != nullptr && last_->first == toolLength) return last_->second;  // a tool stays for many lines
    auto it = cache_.find(toolLength);
    if (it == cache_.end()) {
      auto machine = std::make_shared<Machine>(*machine_);
      machine->toolOffset -= toolLength * machine->toolDirection;
      it = cache_.emplace(toolLength, Models{compile(machine, errors_), compileNominal(machine)}).first;
    }
    last_ = &*it;
    return it->second;
  }

 private:
  std::shared_ptr<const Machine> machine_;
  const ErrorModel& errors_;
  std::map<double, Models> cache_;
  const std::pair<const double, Models>* last_ = nullptr;  // the entry asked for last (map entries stay in place)
};

}  // namespace mtacc
