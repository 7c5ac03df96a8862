// SHA-256 (FIPS 180-4) of byte strings and files, as lowercase hex: the content checksum rk-run
// records for every input, tool executable and product, comparable with `sha256sum`. Backed by
// OpenSSL 3's libcrypto (EVP interface), which uses the CPU's SHA instructions where there are any.
#pragma once

#include <cstddef>
#include <memory>
#include <string>
#include <string_view>

namespace rk::run {

class Sha256 {
 public:
  Sha256();
  ~Sha256();
  Sha256(Sha256&&) noexcept;
  Sha256& operator=(Sha256&&) noexcept;
  void Update(const void* data, std::size_t bytes);
  void Update(std::string_view text) { Update(text.data(), text.size()); }
  // Finishes the digest (the object is spent afterwards) and returns 64 hex characters.
  std::string HexDigest();

 private:
  struct Context;  // the EVP_MD_CTX, kept out of this header (no OpenSSL include for the users)
  std::unique_ptr<Context> ctx_;
};

std::string Sha256Hex(std::string_view text);
// Hashes a file by streaming it (constant memory). Throws IoError if it cannot be read.
std::string Sha256File(const std::string& path);

}  // namespace rk::run
