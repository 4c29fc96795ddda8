#pragma once
// Files as text. Inputs are read whole or line by line in bounded memory (a directory or a
// missing file is an InputError, not an empty text); outputs are written whole or not at all:
// to a temporary file beside the target, then renamed over it.
#include <cstdint>
#include <fstream>
#include <string>
#include <string_view>

namespace mtacc {

// Throws InputError naming the path when it is not a readable regular file.
std::string readTextFile(const std::string& path);
// Throws InputError naming the path when the file cannot be written, under `key` (the option
// or argument that named the file).
void writeFileAtomically(const std::string& path, const std::string& content, const std::string& key = "output");

// A text file read line by line, a block of 1 MiB at a time: each line without its newline (and
// a '\r' before it), as readTextFile's text split at '\n' gives them; a last line without a
// newline is a line, nothing after the last newline is not.
class TextLines {
 public:
  explicit TextLines(const std::string& path);  // throws InputError as readTextFile does
  // The next line, valid until the next call; false at the end.
  bool next(std::string_view& line);
  std::uint64_t bytesRead() const { return consumed_; }  // up to the end of the last line given
  std::uint64_t size() const { return size_; }

 private:
  void fill();
  std::string path_;
  std::ifstream in_;
  std::string block_;
  size_t begin_ = 0;
  bool end_ = false;
  std::uint64_t consumed_ = 0, size_ = 0;
};

// An output file written as it is produced: to a temporary file beside the target, which
// commit() renames over it; destroyed uncommitted (an error on the way), it removes the
// temporary and leaves the target as it was.
class AtomicFile {
 public:
  AtomicFile(const std::string& path, const std::string& key);
  AtomicFile(const AtomicFile&) = delete;
  AtomicFile& operator=(const AtomicFile&) = delete;
  ~AtomicFile();
  void write(std::string_view text);    // throws InputError when the disk refuses it
  void append(AtomicFile& other);  // what `other` has written so far, copied a block at a time
  void commit();

 private:
  void check();
  std::string path_, key_, temporary_;
  std::ofstream out_;
  bool committed_ = false;
};

}  // namespace mtacc
