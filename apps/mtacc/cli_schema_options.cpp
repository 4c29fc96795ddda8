// The CLI's flags of a workflow's option schema: one generic mapping, so that a new option is
// declared in the workflow alone.
#include <algorithm>

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

}  // namespace

void addSchemaOptions(CLI::App& cmd, const OptionSchema& schema, OptionValues& values, const std::map<std::string, std::string>& aliases) {
  for (const OptionField& field : schema.fields) {
    std::string flag = field.positional ? field.key : "--" + field.key;
    std::replace(flag.begin(), flag.end(), '_', '-');
    if (const auto alias = aliases.find(field.key); alias != aliases.end()) flag += "," + alias->second;
    const std::string help = optionHelp(field);
    const std::string key = field.key;
    if (field.kind == OptionKind::Flag)
      cmd.add_flag_callback(flag, [&values, key] { values[key] = {"true"}; }, help);
    else if (field.kind == OptionKind::List || field.kind == OptionKind::Numbers)
      cmd.add_option_function<std::vector<std::string>>(flag, [&values, key](const std::vector<std::string>& given) { values[key] = given; },
                                                        help)
          ->type_name(typeName(field));
    else
      cmd.add_option_function<std::string>(flag, [&values, key](const std::string& given) { values[key] = {given}; }, help)
          ->type_name(typeName(field))
          ->required(field.positional || field.required);
  }
}

}  // namespace mtacc::cli
