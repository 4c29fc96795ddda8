#include "command_line.hpp"

#include <CLI/CLI.hpp>

#include <algorithm>
#include <vector>

#include "cli_common.hpp"

namespace mtacc::cli {
namespace {

std::string typeName(const OptionField& field) {
  switch (field.kind) {
    case OptionKind::Count: return "INT";
    case OptionKind::Number:
    case OptionKind::Numbers: return "FLOAT";
    case OptionKind::Quantity: return field.dimension == Dimension::Length ? "LENGTH" : "ANGLE";
    default: return "TEXT";
  }
}

// A workpiece load in kg, 0 to 1e6 (--load).
CLI::Validator loadInKg() {
  return CLI::Validator(
      [](const std::string& text) {
        double kg = -1.0;
        return CLI::detail::lexical_cast(text, kg) && kg >= 0.0 && kg <= 1e6 ? std::string()
                                                                             : "'" + text + "' is not a load: expected 0 to 1e6 kg";
      },
      "KG");
}

}  // namespace

CommandLine CommandLine::subcommand(const std::string& name, const std::string& help) const { return CommandLine(*app_->add_subcommand(name, help)); }

void CommandLine::requireSubcommand() const { app_->require_subcommand(1); }

void CommandLine::alias(const std::string& name) const { app_->alias(name); }

void CommandLine::argument(const std::string& name, std::string& value, const std::string& help) const {
  app_->add_option(name, value, help)->required();
}

void CommandLine::option(const std::string& flags, std::string& value, const std::string& help) const { app_->add_option(flags, value, help); }

void CommandLine::option(const std::string& flags, int& value, const std::string& help) const { app_->add_option(flags, value, help); }

void CommandLine::flag(const std::string& flags, bool& value, const std::string& help) const { app_->add_flag(flags, value, help); }

void CommandLine::requireOption(const std::string& flag) const { app_->get_option(flag)->required(); }

void CommandLine::callback(std::function<void()> run) const { app_->callback(std::move(run)); }

// One generic mapping of a schema to flags, so that a new option is declared in the workflow alone.
void CommandLine::schemaOptions(const OptionSchema& schema, OptionValues& values, const std::map<std::string, std::string>& aliases) const {
  for (const OptionField& field : schema.fields) {
    std::string flag = field.positional ? field.key : "--" + field.key;
    std::replace(flag.begin(), flag.end(), '_', '-');
    if (const auto alias = aliases.find(field.key); alias != aliases.end()) flag += "," + alias->second;
    const std::string help = optionHelp(field);
    const std::string key = field.key;
    if (field.kind == OptionKind::Flag)
      app_->add_flag_callback(flag, [&values, key] { values[key] = {"true"}; }, help);
    else if (field.kind == OptionKind::List || field.kind == OptionKind::Numbers)
      app_->add_option_function<std::vector<std::string>>(flag, [&values, key](const std::vector<std::string>& given) { values[key] = given; },
                                                          help)
          ->type_name(typeName(field));
    else
      app_->add_option_function<std::string>(flag, [&values, key](const std::string& given) { values[key] = {given}; }, help)
          ->type_name(typeName(field))
          ->required(field.positional || field.required);
  }
}

void CommandLine::machineOptions(MachineOptions& o) const {
  argument("machine", o.source.machine, "machine file, or the name of a bundled machine (e.g. tilting-table)");
  option("--errors", o.source.errorsFile, "errors file (YAML with an 'errors:' mapping); default: the machine file's");
  option("--alignment", o.source.alignment,
         "workpiece set-up: 'table' (fixed to the table frame) or 'machine' (aligned at the reference pose, "
         "the workpiece-to-table transformation M_WC of Li et al. 2021); default: the machine file's");
  app_->add_option_function<double>(
          "--load", [&o](double kg) { o.source.load = kg; },
          "workpiece load on the table in kg, scaling the errors' load-dependent stiffness changes; default: the errors' "
          "workpiece_load")
      ->check(loadInKg());
  option("--thermal", o.source.thermalFile, "thermal state (YAML: the temperatures along the scales, docs/file-formats.md); default: cold, 20 degC");
  outputOptions(o);
}

void CommandLine::outputOptions(MachineOptions& o) const {
  flag("--json", o.json, "print one JSON object instead of tables");
  option("-o,--output", o.output, "write the result to FILE (CSV, or JSON with --json), atomically");
}

}  // namespace mtacc::cli
