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
    ::madvise(p, size_, MADV_SEQUENTIAL);
    data_ = static_cast<const std::uint8_t*>(p);
  }
  ::close(fd);
}

MappedFile::~MappedFile() {
  if (data_) ::munmap(const_cast<std::uint8_t*>(data_), size_);
}

void MappedFile::WillNeed(std::uint64_t offset, std::uint64_t n) const {
  if (!data_ || offset >= size_) return;
  const std::uint64_t page = static_cast<std::uint64_t>(::sysconf(_SC_PAGESIZE));
  const std::uint64_t start = offset / page * page;
  const std::uint64_t end = std::min(size_, offset + n);
  ::madvise(const_cast<std::uint8_t*>(data_) + start, end - start, MADV_WILLNEED);
}

}  // namespace rk::video
