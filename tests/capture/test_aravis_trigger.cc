// The frame's time of a triggered GigE Vision camera (capture/aravis_source.h DecideTrigger): a hardware trigger
// on FrameStart makes the frame's time the trigger's, the camera's stamp (exposure start) less TriggerDelay (µs,
// SFNC) or TriggerDelayAbs (older cameras); a software trigger, a trigger that does not start each frame, or a
// camera in free run keep the stamp. The features are read through a map standing in for the camera's nodes.
#include <gtest/gtest.h>

#include <map>
#include <optional>
#include <string>

#include "capture/aravis_source.h"

namespace rk::capture {
namespace {

TriggerTiming Decide(const std::map<std::string, std::string>& camera) {
  return DecideTrigger([&](const char* name) -> std::optional<std::string> {
    const auto it = camera.find(name);
    if (it == camera.end()) return std::nullopt;
    return it->second;
  });
}

TEST(AravisTrigger, FreeRunKeepsTheStamp) {
  const TriggerTiming t = Decide({{"TriggerMode", "Off"}, {"TriggerSource", "Line1"}, {"TriggerDelay", "50"}});
  EXPECT_FALSE(t.hardware);
  EXPECT_EQ(t.delay_ns, 0);
  EXPECT_TRUE(t.report.is_null());
  EXPECT_FALSE(Decide({}).hardware);  // a camera without trigger controls
}

TEST(AravisTrigger, HardwareTriggerSubtractsTheDelay) {
  const TriggerTiming t = Decide(
      {{"TriggerSelector", "FrameStart"}, {"TriggerMode", "On"}, {"TriggerSource", "Line1"}, {"TriggerDelay", "12.5"}});
  EXPECT_TRUE(t.hardware);
  EXPECT_EQ(t.delay_ns, 12500);
  EXPECT_EQ(t.report["delay_feature"], "TriggerDelay");
  EXPECT_DOUBLE_EQ(t.report["delay_s"].get<double>(), 12.5e-6);
  // An older camera's name for it.
  const TriggerTiming old = Decide({{"TriggerMode", "On"}, {"TriggerSource", "Line0"}, {"TriggerDelayAbs", "300"}});
  EXPECT_TRUE(old.hardware);
  EXPECT_EQ(old.delay_ns, 300000);
  EXPECT_EQ(old.report["delay_feature"], "TriggerDelayAbs");
}

TEST(AravisTrigger, HardwareTriggerWithoutADelayFeatureSaysSo) {
  const TriggerTiming t = Decide({{"TriggerMode", "On"}, {"TriggerSource", "Line0"}});
  EXPECT_TRUE(t.hardware);
  EXPECT_EQ(t.delay_ns, 0);
  EXPECT_NE(t.report["frame_time"].get<std::string>().find("no TriggerDelay"), std::string::npos);
  // A delay that is not a number of µs is not used.
  EXPECT_EQ(Decide({{"TriggerMode", "On"}, {"TriggerSource", "Line0"}, {"TriggerDelay", "soon"}}).delay_ns, 0);
  EXPECT_EQ(Decide({{"TriggerMode", "On"}, {"TriggerSource", "Line0"}, {"TriggerDelay", "-4"}}).delay_ns, 0);
}

TEST(AravisTrigger, SoftwareAndNonFrameTriggersKeepTheStamp) {
  EXPECT_FALSE(Decide({{"TriggerMode", "On"}, {"TriggerSource", "Software"}, {"TriggerDelay", "10"}}).hardware);
  const TriggerTiming acq = Decide({{"TriggerSelector", "AcquisitionStart"},
                                    {"TriggerMode", "On"},
                                    {"TriggerSource", "Line1"},
                                    {"TriggerDelay", "10"}});
  EXPECT_FALSE(acq.hardware);
  EXPECT_EQ(acq.delay_ns, 0);
  EXPECT_NE(acq.report["frame_time"].get<std::string>().find("AcquisitionStart"), std::string::npos);
}

}  // namespace
}  // namespace rk::capture
