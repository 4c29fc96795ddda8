#include "mtacc/core/text_file.hpp"

#include <fmt/format.h>

#include <unistd.h>

#include <atomic>
#include <cstdio>
#include <filesystem>
#include <fstream>
#include <sstream>

#include "mtacc/core/input_error.hpp"

namespace mtacc {

std::string readTextFile(const std::string& path) {
  namespace fs = std::filesystem;
  std::error_code ec;
  const auto status = fs::status(path, ec);
  if (!fs::exists(status)) throw InputError(InputLocation{path, 0, ""}, "no such file");
  if (fs::is_directory(status)) throw InputError(InputLocation{path, 0, ""}, "is a directory, not a file");
  std::ifstream in(path, std::ios::binary);
  if (!in) throw InputError(InputLocation{path, 0, ""}, "cannot open file");
  std::stringstream buffer;
  buffer << in.rdbuf();
  return buffer.str();
}

void writeFileAtomically(const std::string& path, const std::string& content, const std::string& key) {
  AtomicFile file(path, key);
  file.write(content);
  file.commit();
}

namespace {

constexpr size_t kBlock = size_t{1} << 20;

}  // namespace

TextLines::TextLines(const std::string& path) : path_(path) {
  namespace fs = std::filesystem;
  std::error_code ec;
  const auto status = fs::status(path, ec);
  if (!fs::exists(status)) throw InputError(InputLocation{path, 0, ""}, "no such file");
  if (fs::is_directory(status)) throw InputError(InputLocation{path, 0, ""}, "is a directory, not a file");
  in_.open(path, std::ios::binary);
  if (!in_) throw InputError(InputLocation{path, 0, ""}, "cannot open file");
  const auto bytes = fs::file_size(path, ec);
  size_ = ec ? 0 : bytes;
}

void TextLines::fill() {
  block_.erase(0, begin_);
  begin_ = 0;
  const size_t kept = block_.size();
  block_.resize(kept + kBlock);
  in_.read(block_.data() + kept, static_cast<std::streamsize>(kBlock));
  block_.resize(kept + static_cast<size_t>(in_.gcount()));
  if (in_.bad()) throw InputError(InputLocation{path_, 0, ""}, "reading the file failed");
  if (in_.gcount() == 0) end_ = true;
}

bool TextLines::next(std::string_view& line) {
  for (;;) {
    const size_t newline = block_.find('\n', begin_);
    if (newline != std::string::npos || (end_ && begin_ < block_.size())) {
      const size_t stop = newline == std::string::npos ? block_.size() : newline;
      line = std::string_view(block_).substr(begin_, stop - begin_);
      if (!line.empty() && line.back() == '\r') line.remove_suffix(1);
      consumed_ += (newline == std::string::npos ? stop : stop + 1) - begin_;
      begin_ = newline == std::string::npos ? stop : stop + 1;
      return true;
    }
    if (end_) return false;
    fill();
  }
}

AtomicFile::AtomicFile(const std::string& path, const std::string& key) : path_(path), key_(key) {
  namespace fs = std::filesystem;
  static std::atomic<int> counter = 0;
  const fs::path target(path);
  if (fs::is_directory(target)) throw InputError(InputLocation{"", 0, key}, "'" + path + "' is a folder; name an output file");
  const fs::path dir = target.has_parent_path() ? target.parent_path() : fs::path(".");
  temporary_ = (dir / fmt::format(".{}.tmp{}-{}", target.filename().string(), ::getpid(), counter++)).string();
  out_.open(temporary_, std::ios::binary | std::ios::trunc);
  if (!out_) throw InputError(InputLocation{"", 0, key}, "cannot write '" + path + "' (does its folder exist?)");
}

AtomicFile::~AtomicFile() {
  if (committed_) return;
  out_.close();
  std::error_code ec;
  std::filesystem::remove(temporary_, ec);
}

void AtomicFile::check() {
  if (!out_) throw InputError(InputLocation{"", 0, key_}, "writing '" + path_ + "' failed (is the disk full?)");
}

void AtomicFile::write(std::string_view text) {
  out_.write(text.data(), static_cast<std::streamsize>(text.size()));
  check();
}

void AtomicFile::append(AtomicFile& other) {
  other.out_.flush();
  other.check();
  std::ifstream in(other.temporary_, std::ios::binary);
  std::string block(kBlock, '\0');
  while (in.read(block.data(), static_cast<std::streamsize>(block.size())) || in.gcount() > 0)
    write(std::string_view(block.data(), static_cast<size_t>(in.gcount())));
  if (in.bad()) throw InputError(InputLocation{"", 0, key_}, "copying into '" + path_ + "' failed");
}

void AtomicFile::commit() {
  out_.flush();
  check();
  out_.close();
  std::error_code ec;
  std::filesystem::rename(temporary_, path_, ec);
  if (ec) throw InputError(InputLocation{"", 0, key_}, "cannot move '" + path_ + "' into place: " + ec.message());
  committed_ = true;
}

}  // namespace mtacc
