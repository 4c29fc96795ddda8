#include "mtacc/io/file_hash.hpp"

#include <fmt/format.h>
#include <openssl/evp.h>

#include <stdexcept>

#include "mtacc/core/text_file.hpp"

namespace mtacc {

std::string sha256OfFile(const std::string& path) {
  const std::string content = readTextFile(path);
  unsigned char digest[EVP_MAX_MD_SIZE];
  unsigned int length = 0;
  if (EVP_Digest(content.data(), content.size(), digest, &length, EVP_sha256(), nullptr) != 1)
    throw std::runtime_error("SHA-256 of " + path + " failed");
  std::string hex;
  for (unsigned int i = 0; i < length; ++i) hex += fmt::format("{:02x}", digest[i]);
  return hex;
}

}  // namespace mtacc
