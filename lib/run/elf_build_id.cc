#include "run/elf_build_id.h"

#include <elf.h>

#include <cstring>
#include <fstream>
#include <vector>

namespace rk::run {

std::string ElfBuildId(const std::string& path) {
  std::ifstream in(path, std::ios::binary);
  if (!in) return "";
  Elf64_Ehdr eh{};
  if (!in.read(reinterpret_cast<char*>(&eh), sizeof eh)) return "";
  if (std::memcmp(eh.e_ident, ELFMAG, SELFMAG) != 0 || eh.e_ident[EI_CLASS] != ELFCLASS64 ||
      eh.e_ident[EI_DATA] != ELFDATA2LSB || eh.e_phentsize != sizeof(Elf64_Phdr) || eh.e_phnum == 0 ||
      eh.e_phnum > 512) {
    return "";
  }
  std::vector<Elf64_Phdr> ph(eh.e_phnum);
  in.seekg(static_cast<std::streamoff>(eh.e_phoff));
  if (!in.read(reinterpret_cast<char*>(ph.data()), static_cast<std::streamsize>(ph.size() * sizeof(Elf64_Phdr)))) {
    return "";
  }
  constexpr std::uint64_t kMaxNotes = 1 << 16;  // note segments are small; anything larger is not one
  for (const auto& p : ph) {
    if (p.p_type != PT_NOTE || p.p_filesz == 0 || p.p_filesz > kMaxNotes) continue;
    std::vector<unsigned char> notes(p.p_filesz);
    in.seekg(static_cast<std::streamoff>(p.p_offset));
    if (!in.read(reinterpret_cast<char*>(notes.data()), static_cast<std::streamsize>(notes.size()))) return "";
    const auto align4 = [](std::uint64_t n) { return (n + 3) & ~std::uint64_t{3}; };
    std::uint64_t off = 0;
    while (off + sizeof(Elf64_Nhdr) <= notes.size()) {
      Elf64_Nhdr nh;
      std::memcpy(&nh, notes.data() + off, sizeof nh);
      const std::uint64_t name_at = off + sizeof nh;
      const std::uint64_t desc_at = name_at + align4(nh.n_namesz);
      const std::uint64_t next = desc_at + align4(nh.n_descsz);
      if (desc_at + nh.n_descsz > notes.size()) break;
      if (nh.n_type == NT_GNU_BUILD_ID && nh.n_namesz == 4 && std::memcmp(notes.data() + name_at, "GNU", 4) == 0 &&
          nh.n_descsz > 0) {
        static const char* const kHex = "0123456789abcdef";
        std::string hex;
        for (std::uint64_t i = 0; i < nh.n_descsz; ++i) {
          hex.push_back(kHex[notes[desc_at + i] >> 4]);
          hex.push_back(kHex[notes[desc_at + i] & 0xf]);
        }
        return hex;
      }
      off = next;
    }
  }
  return "";
}

}  // namespace rk::run
