#include "mtacc/io/npy.hpp"

#include <fmt/format.h>

#include <bit>
#include <cstdint>
#include <cstring>
#include <optional>

#include "mtacc/core/input_error.hpp"

namespace mtacc {
namespace {

static_assert(std::endian::native == std::endian::little, "the .npy data is read as little-endian float64 in place");

constexpr char kMagic[] = "\x93NUMPY";
constexpr size_t kMagicSize = 6;
constexpr size_t kLargestHeader = 1 << 20;  // bytes; NumPy's own limit is far below
constexpr int kDeepestNesting = 4;

// A Python literal as NumPy's header writes them: strings, integers, True/False, tuples, lists
// and one dictionary with string keys.
struct Literal {
  enum class Kind { String, Integer, Boolean, Sequence, Dictionary };
  explicit Literal(Kind k) : kind(k) {}
  Kind kind;
  std::string text;  // String
  uint64_t integer = 0;
  bool boolean = false;
  std::vector<Literal> items;                               // Sequence
  std::vector<std::pair<std::string, Literal>> entries;     // Dictionary
};

class HeaderParser {
 public:
  HeaderParser(const std::string& text, const std::string& source) : text_(text), source_(source) {}

  Literal parse() {
    Literal value = literal(0);
    skipSpace();
    if (at_ != text_.size()) fail("text after the header's dictionary");
    if (value.kind != Literal::Kind::Dictionary) fail("the header is not a dictionary");
    return value;
  }

 private:
  [[noreturn]] void fail(const std::string& why) const {
    throw InputError({source_, 0, "header"}, fmt::format("{} at byte {} of the .npy header", why, at_));
  }
  void skipSpace() {
    while (at_ < text_.size() && (text_[at_] == ' ' || text_[at_] == '\n' || text_[at_] == '\t')) ++at_;
  }
  bool take(char c) {
    skipSpace();
    if (at_ < text_.size() && text_[at_] == c) {
      ++at_;
      return true;
    }
    return false;
  }

  Literal literal(int depth) {
    if (depth > kDeepestNesting) fail("nesting too deep");
    skipSpace();
    if (at_ >= text_.size()) fail("the header ends early");
    const char c = text_[at_];
    if (c == '\'' || c == '"') {
      Literal value(Literal::Kind::String);
      value.text = string();
      return value;
    }
    if (c >= '0' && c <= '9') return integer();
    if (c == '{') return dictionary(depth);
    if (c == '(' || c == '[') return sequence(depth, c == '(' ? ')' : ']');
    for (const bool b : {true, false}) {
      const std::string word = b ? "True" : "False";
      if (text_.compare(at_, word.size(), word) == 0) {
        at_ += word.size();
        Literal value(Literal::Kind::Boolean);
        value.boolean = b;
        return value;
      }
    }
    fail(fmt::format("unexpected '{}'", c));
  }

  std::string string() {
    const char quote = text_[at_++];
    const size_t end = text_.find(quote, at_);
    if (end == std::string::npos) fail("a string without its closing quote");
    std::string s = text_.substr(at_, end - at_);
    if (s.find('\\') != std::string::npos) fail("an escape in a string");
    at_ = end + 1;
    return s;
  }

  Literal integer() {
    Literal value(Literal::Kind::Integer);
    while (at_ < text_.size() && text_[at_] >= '0' && text_[at_] <= '9') {
      const uint64_t digit = static_cast<uint64_t>(text_[at_++] - '0');
      if (value.integer > (UINT64_MAX - digit) / 10) fail("an integer too large");
      value.integer = value.integer * 10 + digit;
    }
    if (at_ < text_.size() && text_[at_] == 'L') ++at_;  // Python 2's long
    return value;
  }

  Literal sequence(int depth, char close) {
    ++at_;
    Literal value(Literal::Kind::Sequence);
    while (!take(close)) {
      value.items.push_back(literal(depth + 1));
      if (!take(',')) {
        if (!take(close)) fail(fmt::format("expected ',' or '{}'", close));
        break;
      }
    }
    return value;
  }

  Literal dictionary(int depth) {
    ++at_;
    Literal value(Literal::Kind::Dictionary);
    while (!take('}')) {
      const Literal key = literal(depth + 1);
      if (key.kind != Literal::Kind::String) fail("a dictionary key that is not a string");
      if (!take(':')) fail("expected ':'");
      value.entries.emplace_back(key.text, literal(depth + 1));
      if (!take(',')) {
        if (!take('}')) fail("expected ',' or '}'");
        break;
      }
    }
    return value;
  }

  const std::string& text_;
  const std::string& source_;
  size_t at_ = 0;
};

const Literal* entry(const Literal& dictionary, const std::string& key) {
  for (const auto& [name, value] : dictionary.entries)
    if (name == key) return &value;
  return nullptr;
}

uint32_t littleEndian(const std::string& bytes, size_t at, size_t width) {
  uint32_t v = 0;
  for (size_t i = 0; i < width; ++i) v |= static_cast<uint32_t>(static_cast<unsigned char>(bytes[at + i])) << (8 * i);
  return v;
}

}  // namespace

NpyRecords parseNpyRecords(const std::string& bytes, const std::string& source) {
  const auto fail = [&](const std::string& key, const std::string& why) { throw InputError({source, 0, key}, why); };
  if (bytes.size() < kMagicSize + 4 || bytes.compare(0, kMagicSize, kMagic, kMagicSize) != 0)
    fail("", "not a NumPy .npy file (no \\x93NUMPY magic)");
  const int major = static_cast<unsigned char>(bytes[6]);
  if (major < 1 || major > 3) fail("", fmt::format(".npy format version {} (1, 2 and 3 are read)", major));
  const size_t lengthWidth = major == 1 ? 2 : 4, headerStart = kMagicSize + 2 + lengthWidth;
  if (bytes.size() < headerStart) fail("header", "the file ends inside the header length");
  const size_t headerLength = littleEndian(bytes, kMagicSize + 2, lengthWidth);
  if (headerLength > kLargestHeader || bytes.size() - headerStart < headerLength)
    fail("header", fmt::format("a header of {} bytes in a file of {}", headerLength, bytes.size()));
  const std::string header = bytes.substr(headerStart, headerLength);
  const Literal dictionary = HeaderParser(header, source).parse();

  const Literal* descr = entry(dictionary, "descr");
  const Literal* fortran = entry(dictionary, "fortran_order");
  const Literal* shape = entry(dictionary, "shape");
  if (!descr || !fortran || !shape) fail("header", "the header lacks one of descr, fortran_order, shape");
  if (fortran->kind != Literal::Kind::Boolean) fail("fortran_order", "not True or False");
  if (descr->kind != Literal::Kind::Sequence)
    fail("descr", "a plain array; save a structured array with one named '<f8' field per channel (np.rec.fromarrays)");
  NpyRecords records;
  for (const auto& field : descr->items) {
    if (field.kind != Literal::Kind::Sequence || field.items.size() != 2 || field.items[0].kind != Literal::Kind::String ||
        field.items[1].kind != Literal::Kind::String)
      fail("descr", "a field that is not a (name, type) pair of strings");
    const auto& name = field.items[0].text;
    if (field.items[1].text != "<f8") fail("descr." + name, fmt::format("type '{}'; each field must be little-endian float64 ('<f8')", field.items[1].text));
    for (const auto& seen : records.names)
      if (seen == name) fail("descr." + name, "a field name given twice");
    records.names.push_back(name);
  }
  if (records.names.empty()) fail("descr", "no fields");
  if (shape->kind != Literal::Kind::Sequence || shape->items.size() != 1 || shape->items[0].kind != Literal::Kind::Integer)
    fail("shape", "the array is not one-dimensional");
  const uint64_t count = shape->items[0].integer;
  const size_t recordBytes = 8 * records.names.size(), dataBytes = bytes.size() - headerStart - headerLength;
  if (count > dataBytes / recordBytes || count * recordBytes != dataBytes)
    fail("shape", fmt::format("{} records of {} bytes, but {} bytes of data follow the header", count, recordBytes, dataBytes));

  const char* data = bytes.data() + headerStart + headerLength;
  records.columns.assign(records.names.size(), std::vector<double>(count));
  for (size_t k = 0; k < count; ++k)
    for (size_t f = 0; f < records.names.size(); ++f) std::memcpy(&records.columns[f][k], data + (k * records.names.size() + f) * 8, 8);
  return records;
}

std::string npyRecords(const NpyRecords& records) {
  std::vector<std::string> fields;
  for (const auto& name : records.names) fields.push_back(fmt::format("('{}', '<f8')", name));
  const std::string descr = fmt::format("{}", fmt::join(fields, ", "));
  const size_t count = records.columns.empty() ? 0 : records.columns.front().size();
  std::string header = fmt::format("{{'descr': [{}], 'fortran_order': False, 'shape': ({},), }}", descr, count);
  const size_t preamble = kMagicSize + 4;
  header.append(63 - (preamble + header.size()) % 64, ' ');
  header += '\n';
  std::string out(kMagic, kMagicSize);
  out += '\x01';
  out += '\x00';
  out += static_cast<char>(header.size() & 0xff);
  out += static_cast<char>(header.size() >> 8);
  out += header;
  const size_t start = out.size();
  out.resize(start + count * records.names.size() * 8);
  for (size_t k = 0; k < count; ++k)
    for (size_t f = 0; f < records.names.size(); ++f) std::memcpy(out.data() + start + (k * records.names.size() + f) * 8, &records.columns[f][k], 8);
  return out;
}

}  // namespace mtacc
