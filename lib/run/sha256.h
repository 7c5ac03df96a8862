// SHA-256 (FIPS 180-4) of byte strings and files, as lowercase hex: the content checksum rk-run
// records for every input, tool executable and product, comparable with `sha256sum`.
#pragma once

#include <array>
#include <cstddef>
#include <cstdint>
#include <string>
#include <string_view>

namespace rk::run {

class Sha256 {
 public:
  Sha256();
  void Update(const void* data, std::size_t bytes);
  void Update(std::string_view text) { Update(text.data(), text.size()); }
  // Finishes the digest (the object is spent afterwards) and returns 64 hex characters.
  std::string HexDigest();

 private:
  void Block(const std::uint8_t* block);
  std::array<std::uint32_t, 8> h_;
  std::array<std::uint8_t, 64> buffer_{};
  std::size_t buffered_ = 0;
  std::uint64_t total_bytes_ = 0;
};

std::string Sha256Hex(std::string_view text);
// Hashes a file by streaming it (constant memory). Throws IoError if it cannot be read.
std::string Sha256File(const std::string& path);

}  // namespace rk::run
