// Shared by the libFuzzer harnesses (README.md). A harness feeds its input to the real parsing entry
// points inside ExpectOnlyInputErrors: rk::Error (the typed input errors, SPEC §4) is the expected
// outcome of bad input; any other exception escapes LLVMFuzzerTestOneInput and aborts the run, as do
// sanitizer reports and failed checks.
#pragma once

#include <unistd.h>

#include <cstdint>
#include <cstdlib>
#include <fstream>
#include <string>
#include <string_view>

#include "io/error.h"

namespace rk::fuzz {

template <class Body>
void ExpectOnlyInputErrors(Body&& body) {
  try {
    body();
  } catch (const rk::Error&) {
    // Bad input, reported the way the tools report it: expected.
  }
}

inline std::string_view AsText(const std::uint8_t* data, std::size_t size) {
  return {reinterpret_cast<const char*>(data), size};
}

// A private folder for parsers that only take a path (made once per process, removed at exit; the
// name is never destroyed, so the exit handler can still use it).
inline const std::string& ScratchDir() {
  static const std::string& dir = *[] {
    const char* tmp = std::getenv("TMPDIR");
    auto* name = new std::string(std::string(tmp && *tmp ? tmp : "/tmp") + "/rk-fuzz-XXXXXX");
    if (!::mkdtemp(name->data())) std::abort();
    return name;
  }();
  static const int removed_at_exit = std::atexit([] { (void)std::system(("rm -rf '" + ScratchDir() + "'").c_str()); });
  (void)removed_at_exit;
  return dir;
}

// Writes `bytes` to ScratchDir()/name and returns the path.
inline std::string WriteScratch(const std::string& name, std::string_view bytes) {
  const std::string path = ScratchDir() + "/" + name;
  std::ofstream out(path, std::ios::binary | std::ios::trunc);
  out.write(bytes.data(), static_cast<std::streamsize>(bytes.size()));
  if (!out.flush()) std::abort();
  return path;
}

}  // namespace rk::fuzz
