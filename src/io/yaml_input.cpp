#include "yaml_input.hpp"

#include <fmt/format.h>

#include <cmath>
#include <fstream>
#include <set>
#include <sstream>
#include <vector>

#include "mtacc/core/input_error.hpp"

namespace mtacc::yamlin {

InputLocation Context::at(const YAML::Node& node, const std::string& key) const {
  const int line = node.IsDefined() && node.Mark().line >= 0 ? node.Mark().line + 1 : 0;
  return InputLocation{file, line, key};
}

void Context::fail(const YAML::Node& node, const std::string& key, const std::string& what) const {
  throw InputError(at(node, key), what);
}

namespace {

// yaml-cpp keeps the first of two equal keys silently, and turns a non-scalar key into a
// "bad conversion" later: both are refused here, at their line, for the whole document. The
// walk keeps its own stack (no recursion on deeply nested input) and stops at a million values
// (aliases can repeat a node exponentially often, or refer to themselves).
void checkKeys(const Context& ctx, const YAML::Node& root) {
  constexpr long kMaxValues = 1000000;
  std::vector<std::pair<YAML::Node, std::string>> pending{{root, ""}};
  long visited = 0;
  while (!pending.empty()) {
    if (++visited > kMaxValues) ctx.fail(root, "", "more than a million values (aliases repeating themselves?)");
    auto [node, path] = std::move(pending.back());
    pending.pop_back();
    if (node.IsSequence()) {
      for (size_t i = 0; i < node.size(); ++i) pending.emplace_back(node[i], fmt::format("{}[{}]", path, i));
    } else if (node.IsMap()) {
      std::set<std::string> seen;
      for (const auto& kv : node) {
        if (!kv.first.IsScalar()) ctx.fail(kv.first, path, "a key must be a plain name, not a list or a mapping");
        const auto key = kv.first.Scalar();
        const std::string keyPath = path.empty() ? key : path + "." + key;
        if (!seen.insert(key).second) ctx.fail(kv.first, keyPath, "key given twice");
        pending.emplace_back(kv.second, keyPath);
      }
    }
  }
}

}  // namespace

YAML::Node loadText(const std::string& text, const std::string& sourceName) {
  YAML::Node root;
  try {
    root = YAML::Load(text);
  } catch (const YAML::Exception& e) {
    throw InputError(InputLocation{sourceName, e.mark.line >= 0 ? e.mark.line + 1 : 0, ""},
                     "malformed YAML: " + e.msg);
  }
  checkKeys(Context{sourceName}, root);
  return root;
}


void rejectUnknownKeys(const Context& ctx, const YAML::Node& map, const std::string& path,
                       std::initializer_list<const char*> allowed) {
  if (!isMap(map)) ctx.fail(map, path, "expected a mapping");
  std::set<std::string> ok(allowed.begin(), allowed.end());
  for (const auto& kv : map) {
    const auto key = kv.first.as<std::string>();
    if (!ok.count(key)) {
      std::string list;
      for (const auto& a : allowed) list += (list.empty() ? "" : ", ") + std::string(a);
      ctx.fail(kv.first, path.empty() ? key : path + "." + key, "unknown key (expected one of: " + list + ")");
    }
  }
}

std::string scalar(const Context& ctx, const YAML::Node& node, const std::string& key) {
  if (!node.IsDefined() || node.IsNull()) ctx.fail(node, key, "missing value");
  if (!node.IsScalar()) ctx.fail(node, key, "expected a single value");
  return node.Scalar();
}

bool boolean(const Context& ctx, const YAML::Node& node, const std::string& key) {
  const auto text = scalar(ctx, node, key);
  bool value = false;
  if (!YAML::convert<bool>::decode(node, value)) ctx.fail(node, key, "expected true or false, got '" + text + "'");
  return value;
}

double number(const Context& ctx, const YAML::Node& node, const std::string& key) {
  const auto text = scalar(ctx, node, key);
  try {
    size_t used = 0;
    const double v = std::stod(text, &used);
    if (used != text.size()) throw InvalidInput("trailing text");
    if (!std::isfinite(v)) ctx.fail(node, key, "value is not finite");
    return v;
  } catch (const std::logic_error&) {
    ctx.fail(node, key, "expected a plain number, got '" + text + "'");
  }
}

Quantity anyQuantity(const Context& ctx, const YAML::Node& node, const std::string& key) {
  const auto text = scalar(ctx, node, key);
  std::string reason;
  const auto q = parseQuantity(text, &reason);
  if (!q) ctx.fail(node, key, reason);
  return *q;
}

int wholeNumber(const Context& ctx, const YAML::Node& node, const std::string& key, int minimum, int maximum) {
  const double v = number(ctx, node, key);
  if (!(v >= minimum && v <= maximum) || v != std::floor(v))
    ctx.fail(node, key, "expected a whole number from " + std::to_string(minimum) + " to " + std::to_string(maximum));
  return static_cast<int>(v);
}

double quantity(const Context& ctx, const YAML::Node& node, const std::string& key, Dimension expected) {
  const auto q = anyQuantity(ctx, node, key);
  if (q.dimension != expected)
    ctx.fail(node, key, fmt::format("expected {} but '{}' is {}", withArticle(expected), node.Scalar(), withArticle(q.dimension)));
  return q.value;
}

double size(const Context& ctx, const YAML::Node& node, const std::string& key, Dimension expected) {
  const double v = quantity(ctx, node, key, expected);
  constexpr double kSmallest = 1e-6;  // 1 nm in mm, 1 urad in rad
  if (!(v >= kSmallest)) ctx.fail(node, key, fmt::format("must be positive (at least 1 {})", expected == Dimension::Length ? "nm" : "urad"));
  return v;
}

Vec3 unitVector(const Context& ctx, const YAML::Node& node, const std::string& key) {
  if (!isSequence(node) || node.size() != 3) ctx.fail(node, key, "expected a vector [x, y, z]");
  Vec3 v;
  for (int i = 0; i < 3; ++i) v[i] = number(ctx, node[i], key);
  const double largest = v.cwiseAbs().maxCoeff();
  if (!(largest > 0)) ctx.fail(node, key, "direction vector has zero length");
  return (v / largest).normalized();
}

Vec3 lengthVector(const Context& ctx, const YAML::Node& node, const std::string& key) {
  if (!isSequence(node) || node.size() != 3) ctx.fail(node, key, "expected a vector [x mm, y mm, z mm]");
  Vec3 v;
  for (int i = 0; i < 3; ++i) v[i] = quantity(ctx, node[i], key, Dimension::Length);
  return v;
}

}  // namespace mtacc::yamlin
