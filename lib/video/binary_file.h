// A camera file mapped into memory (read-only, sequential read-ahead) and bounds-checked reads of its
// little-endian fields: every read past the end, every field out of its range, is a ByteOffsetError
// ("file: byte N: what", exit 3). The parsers of CINE and MRAW files read through a ByteView, so the
// same code parses a mapped file and a fuzzer's buffer.
#pragma once

#include <cstddef>
#include <cstdint>
#include <string>
#include <string_view>
#include <utility>

namespace rk::video {

class ByteView {
 public:
  ByteView(const std::uint8_t* data, std::uint64_t size, std::string file)
      : data_(data), size_(size), file_(std::move(file)) {}

  std::uint64_t size() const { return size_; }
  const std::string& file() const { return file_; }
  const std::uint8_t* data() const { return data_; }

  // The `n` bytes at `offset`; ByteOffsetError naming `what` when they run past the end of the file.
  const std::uint8_t* Need(std::uint64_t offset, std::uint64_t n, std::string_view what) const;
  std::uint16_t U16(std::uint64_t offset, std::string_view what) const;
  std::int32_t I32(std::uint64_t offset, std::string_view what) const;
  std::uint32_t U32(std::uint64_t offset, std::string_view what) const;
  std::uint64_t U64(std::uint64_t offset, std::string_view what) const;
  double F64(std::uint64_t offset, std::string_view what) const;
  [[noreturn]] void Fail(std::uint64_t offset, const std::string& what) const;

 private:
  const std::uint8_t* data_;
  std::uint64_t size_;
  std::string file_;
};

// A whole file mapped read-only, for its headers; its frames are copied out with ReadAt (pread: the kernel's
// copy from the page cache, as dd does — a copy through the mapping pays a TLB miss per 4 KiB page and ran at a
// quarter of dd's speed). IoError when it cannot be opened or mapped; an empty file maps to size 0.
class MappedFile {
 public:
  explicit MappedFile(const std::string& path);
  ~MappedFile();
  MappedFile(const MappedFile&) = delete;
  MappedFile& operator=(const MappedFile&) = delete;

  ByteView view() const { return ByteView(data_, size_, path_); }
  const std::string& path() const { return path_; }
  std::uint64_t size() const { return size_; }
  // Copies the n bytes at `offset` into `dst` (ByteOffsetError naming `what` if they run past the end,
  // IoError if the read fails).
  void ReadAt(std::uint64_t offset, std::uint64_t n, void* dst, std::string_view what) const;
  // The n bytes at `offset` in the mapping, to be read in place (no copy): ByteOffsetError as ReadAt, and
  // IoError if the file is now shorter than the mapping needs (it shrank since it was opened; reading
  // the mapping there would be a SIGBUS).
  const std::uint8_t* MappedAt(std::uint64_t offset, std::uint64_t n, std::string_view what) const;

 private:
  int fd_ = -1;
  std::string path_;
  const std::uint8_t* data_ = nullptr;
  std::uint64_t size_ = 0;
};

}  // namespace rk::video
