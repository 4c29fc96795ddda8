#pragma once
// The small text forms of command-line options and Python arguments: comma lists,
// NAME=value assignments, plain numbers and x,y,z vectors. Every failure is an InputError
// naming `key` (the option or argument).
#include <functional>
#include <optional>
#include <string>
#include <vector>

#include "mtacc/core/transform.hpp"

namespace mtacc {

// "a,b,,c" -> {"a", "b", "c"} (empty items dropped).
std::vector<std::string> splitList(const std::string& text, char separator = ',');
// Without the blanks, tabs and carriage returns at either end.
std::string trim(const std::string& text);
// " a, b,,c," -> {"a", "b", "", "c", ""}: every field, trimmed, empty ones kept (CSV cells).
std::vector<std::string> splitFields(const std::string& text, char separator = ',');

struct Assignment {
  std::string name;
  std::string value;
};
// "X=10,B=-15 deg" -> {{"X", "10"}, {"B", "-15 deg"}}; an item without '=' or without a name is
// an error.
std::vector<Assignment> parseAssignments(const std::string& text, const std::string& key);

// Reads a CSV input with '#' comment lines: `comment(key, value)` for each "# key: value" line
// (free-text comments are skipped), `row(text)` for every other line that is not blank (trimmed).
// `line` holds the current line number throughout, for the callbacks' error messages.
void readCommentedLines(const std::string& text, int& line, const std::function<void(const std::string&, const std::string&)>& comment,
                        const std::function<void(const std::string&)>& row);

// The lines of a text file that are not blank, trimmed, with their 1-based numbers.
struct TextLine {
  int number;
  std::string text;
};
std::vector<TextLine> contentLines(const std::string& text);

// A trimmed comment line "# key: value" of the CSV inputs -> {"key", "value"}; nullopt for a
// comment without a colon (free text).
std::optional<Assignment> commentAssignment(const std::string& line);

// The whole text is one finite number.
double parseNumber(const std::string& text, const std::string& key);
// A whole number within [min, max].
int parseCount(const std::string& text, const std::string& key, int min, int max);
// "x,y,z": exactly three finite numbers.
Vec3 parseVector(const std::string& text, const std::string& key);
// "a, b, ... mm" (the unit after the last, or after each): `count` lengths in mm. Errors say
// "expected FORM" for another count and give `example` for a missing unit.
std::vector<double> parseLengthList(const std::string& text, size_t count, const std::string& key, const std::string& form,
                                    const std::string& example);
// "x, y, z mm": three lengths in mm.
Vec3 parseLengths(const std::string& text, const std::string& key);

}  // namespace mtacc
