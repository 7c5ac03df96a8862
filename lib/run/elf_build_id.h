// The GNU build ID of an ELF executable (the NT_GNU_BUILD_ID note that the linker computes from the
// binary's contents; Debian's toolchain adds it by default). rk-run identifies a tool by its --version
// line plus this ID, which costs one small read instead of hashing the whole executable (tens of MB in a
// sanitizer build); files without a build ID (scripts such as rk-plot) are hashed with SHA-256 instead.
#pragma once

#include <string>

namespace rk::run {

// Lowercase hex of the build ID, or "" if `path` is not a 64-bit little-endian ELF file with one.
std::string ElfBuildId(const std::string& path);

}  // namespace rk::run
