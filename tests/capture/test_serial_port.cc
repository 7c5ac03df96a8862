// Serial port options and the line splitter (capture/serial_port.h).
#include <gtest/gtest.h>

#include <string>

#include "capture/serial_port.h"

namespace rk::capture {
namespace {

TEST(Serial, OptionsAreChecked) {
  SerialOptions o;
  o.port = "/dev/ttyUSB0";
  std::string why;
  EXPECT_TRUE(o.Check(&why));
  EXPECT_EQ(o.BitsPerChar(), 10);
  o.parity = "even";
  EXPECT_EQ(o.BitsPerChar(), 11);
  o.baud = 12345;
  EXPECT_FALSE(o.Check(&why));
  EXPECT_NE(why.find("baud"), std::string::npos);
  o.baud = 9600;
  o.parity = "mark";
  EXPECT_FALSE(o.Check(&why));
  o.parity = "odd";
  o.data_bits = 9;
  EXPECT_FALSE(o.Check(&why));
  o.data_bits = 7;
  o.stop_bits = 3;
  EXPECT_FALSE(o.Check(&why));
}

TEST(Serial, LineSplitterHandlesCrLfAndOverlongRuns) {
  LineSplitter s(16);
  std::vector<std::string> lines;
  const std::string in = "g0g+1\r\ng0g+2\rg0g+3\n\n";
  s.Feed(in.data(), 4, &lines);  // split across feeds
  s.Feed(in.data() + 4, in.size() - 4, &lines);
  ASSERT_EQ(lines.size(), 3u);
  EXPECT_EQ(lines[0], "g0g+1");
  EXPECT_EQ(lines[2], "g0g+3");
  lines.clear();
  const std::string junk(40, 'x');
  s.Feed(junk.data(), junk.size(), &lines);
  s.Feed("\r\nok\r\n", 6, &lines);
  ASSERT_EQ(lines.size(), 1u);
  EXPECT_EQ(lines[0], "ok");
  EXPECT_EQ(s.overlong(), 1u);
  EXPECT_EQ(EscapeForLog(std::string("a\x01\xff", 3)), "a\\x01\\xff");
}

}  // namespace
}  // namespace rk::capture
