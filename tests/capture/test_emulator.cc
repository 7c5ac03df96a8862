// The device emulators' fault specifications (capture/emulator.h).
#include <gtest/gtest.h>

#include <string>

#include "capture/emulator.h"

namespace rk::capture {
namespace {

TEST(Emulator, FaultSpecs) {
  Fault f;
  std::string why;
  ASSERT_TRUE(ParseFault("error:1.5:2", &f, &why)) << why;
  EXPECT_EQ(f.kind, FaultKind::kError);
  EXPECT_EQ(f.code, 255);
  EXPECT_TRUE(f.ActiveAt(1.5));
  EXPECT_TRUE(f.ActiveAt(3.4));
  EXPECT_FALSE(f.ActiveAt(3.5));
  ASSERT_TRUE(ParseFault("error:0:1:256", &f, &why));
  EXPECT_EQ(f.code, 256);
  ASSERT_TRUE(ParseFault("slow:2:1:0.8", &f, &why));
  EXPECT_DOUBLE_EQ(f.delay_s, 0.8);
  ASSERT_TRUE(ParseFault("disconnect:3:0.5", &f, &why));
  EXPECT_EQ(f.kind, FaultKind::kDisconnect);
  for (const char* bad : {"error", "error:1", "boom:1:2", "error:x:2", "error:1:0", "silence:1:2:3", "error:1:2:abc",
                          "slow:1:2:-1", "error:-1:2"}) {
    EXPECT_FALSE(ParseFault(bad, &f, &why)) << bad;
  }
}

}  // namespace
}  // namespace rk::capture
