#pragma once
// A subcommand's command line as the subcommands declare it: a narrow face over CLI11, so that
// only command_line.cpp and main.cpp include CLI11 (7-9 s of compile time in each file that does).
#include <functional>
#include <map>
#include <string>

#include "mtacc/core/option_schema.hpp"

namespace CLI {
class App;
}

namespace mtacc::cli {

struct MachineOptions;

class CommandLine {
 public:
  explicit CommandLine(CLI::App& app) : app_(&app) {}

  CommandLine subcommand(const std::string& name, const std::string& help) const;
  // One of this command's subcommands must be given.
  void requireSubcommand() const;
  void alias(const std::string& name) const;
  // A positional argument that must be given.
  void argument(const std::string& name, std::string& value, const std::string& help) const;
  void option(const std::string& flags, std::string& value, const std::string& help) const;
  void option(const std::string& flags, int& value, const std::string& help) const;
  void flag(const std::string& flags, bool& value, const std::string& help) const;
  // An option declared before (by its long flag) that must be given.
  void requireOption(const std::string& flag) const;
  void callback(std::function<void()> run) const;

  // Adds a flag --key ('_' written '-') for each key of a workflow's schema, storing what is
  // given in `values` for the workflow's reader; `aliases` gives a key further flag names ("--params").
  void schemaOptions(const OptionSchema& schema, OptionValues& values, const std::map<std::string, std::string>& aliases = {}) const;
  // MACHINE, --errors, --alignment, --load, --thermal, --json, -o.
  void machineOptions(MachineOptions& o) const;
  // --json and -o only.
  void outputOptions(MachineOptions& o) const;

 private:
  CLI::App* app_;
};

}  // namespace mtacc::cli
