// Mapped camera files and their bounds-checked fields; see binary_file.h.
#include "video/binary_file.h"

#include <fcntl.h>
#include <sys/mman.h>
#include <sys/stat.h>
#include <unistd.h>

#include <algorithm>
#include <cerrno>
#include <cstring>

#include "io/error.h"

namespace rk::video {

void ByteView::Fail(std::uint64_t offset, const std::string& what) const { throw ByteOffsetError(file_, offset, what); }

const std::uint8_t* ByteView::Need(std::uint64_t offset, std::uint64_t n, std::string_view what) const {
  if (offset > size_ || n > size_ - offset) {
    Fail(offset, std::string(what) + " (" + std::to_string(n) + " bytes) runs past the end of the file (" + std::to_string(size_) +
                     " bytes): truncated or a wrong offset");
  }
  return data_ + offset;
}

namespace {
template <typename T>
T Load(const ByteView& v, std::uint64_t offset, std::string_view what) {
  T out;
  std::memcpy(&out, v.Need(offset, sizeof(T), what), sizeof(T));  // little-endian host (packed_pixels.cc)
  return out;
}
}  // namespace

std::uint16_t ByteView::U16(std::uint64_t offset, std::string_view what) const { return Load<std::uint16_t>(*this, offset, what); }
std::int32_t ByteView::I32(std::uint64_t offset, std::string_view what) const { return Load<std::int32_t>(*this, offset, what); }
std::uint32_t ByteView::U32(std::uint64_t offset, std::string_view what) const { return Load<std::uint32_t>(*this, offset, what); }
std::uint64_t ByteView::U64(std::uint64_t offset, std::string_view what) const { return Load<std::uint64_t>(*this, offset, what); }
double ByteView::F64(std::uint64_t offset, std::string_view what) const { return Load<double>(*this, offset, what); }

MappedFile::MappedFile(const std::string& path) : path_(path) {
  const int fd = ::open(path.c_str(), O_RDONLY | O_CLOEXEC);
  if (fd < 0) throw IoError(path, std::string("cannot open for reading: ") + std::strerror(errno));
  struct stat st {};
  if (::fstat(fd, &st) != 0 || !S_ISREG(st.st_mode)) {
    ::close(fd);
    throw IoError(path, "not a regular file");
  }
  size_ = static_cast<std::uint64_t>(st.st_size);
  if (size_ > 0) {
    void* p = ::mmap(nullptr, size_, PROT_READ, MAP_PRIVATE, fd, 0);
    if (p == MAP_FAILED) {
      const int e = errno;
      ::close(fd);
      throw IoError(path, std::string("cannot map the file: ") + std::strerror(e));
    }
    data_ = static_cast<const std::uint8_t*>(p);
  }
  ::posix_fadvise(fd, 0, 0, POSIX_FADV_SEQUENTIAL);
  fd_ = fd;
}

MappedFile::~MappedFile() {
  if (data_) ::munmap(const_cast<std::uint8_t*>(data_), size_);
  if (fd_ >= 0) ::close(fd_);
}

void MappedFile::ReadAt(std::uint64_t offset, std::uint64_t n, void* dst, std::string_view what) const {
  view().Need(offset, n, what);
  auto* out = static_cast<std::uint8_t*>(dst);
  while (n > 0) {
    const ssize_t got = ::pread(fd_, out, n, static_cast<off_t>(offset));
    if (got < 0 && errno == EINTR) continue;
    if (got <= 0) throw IoError(path_, std::string("cannot read ") + std::string(what) + ": " + (got < 0 ? std::strerror(errno) : "the file shrank"));
    out += got;
    offset += static_cast<std::uint64_t>(got);
    n -= static_cast<std::uint64_t>(got);
  }
}

const std::uint8_t* MappedFile::MappedAt(std::uint64_t offset, std::uint64_t n, std::string_view what) const {
  view().Need(offset, n, what);
  struct stat st {};
  if (::fstat(fd_, &st) != 0 || static_cast<std::uint64_t>(st.st_size) < offset + n) {
    throw IoError(path_, std::string("cannot read ") + std::string(what) + ": the file shrank");
  }
  return data_ + offset;
}

}  // namespace rk::video
