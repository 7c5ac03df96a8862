// Unit tests of run/sha256: FIPS 180-4 test vectors, streaming, files.
#include <gtest/gtest.h>

#include <algorithm>
#include <string>

#include "io/error.h"
#include "run/sha256.h"
#include "run_test_util.h"

namespace rk::run {
namespace {
using testing::TempDir;
using testing::Write;

TEST(Sha256, Fips180Vectors) {
  EXPECT_EQ(Sha256Hex(""), "e3b0c44298fc1c149afbf4c8996fb92427ae41e4649b934ca495991b7852b855");
  EXPECT_EQ(Sha256Hex("abc"), "ba7816bf8f01cfea414140de5dae2223b00361a396177a9cb410ff61f20015ad");
  EXPECT_EQ(Sha256Hex("abcdbcdecdefdefgefghfghighijhijkijkljklmklmnlmnomnopnopq"),
            "248d6a61d20638b8e5c026930c3e6039a33ce45964ff2167f6ecedd419db06c1");
}

TEST(Sha256, MillionAStreamedInOddChunks) {
  // One million 'a' fed in chunks of 1, 63, 64, 65, 1000 bytes: block buffering must not matter.
  Sha256 h;
  const std::string chunk(1000, 'a');
  std::size_t done = 0;
  const std::size_t sizes[] = {1, 63, 64, 65, 1000};
  for (int k = 0; done < 1000000; ++k) {
    const std::size_t n = std::min(sizes[k % 5], 1000000 - done);
    h.Update(chunk.data(), n);
    done += n;
  }
  EXPECT_EQ(h.HexDigest(), "cdc76e5c9914fb9281a1c7e284d73e67f1809a48a497200e046d39ccc7112cd0");
}

TEST(Sha256, FileMatchesString) {
  TempDir d;
  Write(d / "f.bin", "abc");
  EXPECT_EQ(Sha256File(d / "f.bin"), Sha256Hex("abc"));
  EXPECT_THROW(Sha256File(d / "missing"), Error);
}

}  // namespace
}  // namespace rk::run
