// Shared by the serial driver tests (test_dimetix.cc, test_ptu.cc): the emulator's log of every reply it
// sent (the truth), an emulator running on its own thread, and a reporter that records events and gaps.
#pragma once

#include <gtest/gtest.h>

#include <atomic>
#include <fstream>
#include <mutex>
#include <string>
#include <thread>
#include <vector>

#include "capture/device.h"
#include "capture/emulator.h"
#include "capture/serial_port.h"

namespace rk::capture {

struct TruthLine {
  double mono_s = 0;
  std::string event, data;
};

inline std::vector<TruthLine> ReadTruth(const std::string& path) {
  std::vector<TruthLine> out;
  std::ifstream in(path);
  std::string line;
  std::getline(in, line);  // header
  while (std::getline(in, line)) {
    const auto a = line.find(','), b = line.find(',', a + 1);
    out.push_back({std::stod(line.substr(0, a)), line.substr(a + 1, b - a - 1), line.substr(b + 1)});
  }
  return out;
}

// Runs an emulator on its own thread for the lifetime of the object.
template <class Emu>
class Running {
 public:
  template <class Opt>
  explicit Running(const Opt& o) : emu_(o) {
    std::string why;
    ok_ = emu_.Start(&why);
    EXPECT_TRUE(ok_) << why;
    if (ok_) thread_ = std::thread([this] { emu_.Run(stop_, 0.0); });
  }
  ~Running() { Stop(); }
  void Stop() {
    stop_ = true;
    if (thread_.joinable()) thread_.join();
  }
  std::string port() const { return emu_.port(); }
  EmulatorStats stats() const { return emu_.stats(); }

 private:
  Emu emu_;
  std::atomic<bool> stop_{false};
  std::thread thread_;
  bool ok_ = false;
};

struct Recorded {
  std::mutex mutex;
  std::vector<std::string> events;
  int gaps_begun = 0, gaps_ended = 0;
  DeviceReporter Reporter() {
    DeviceReporter r;
    r.event = [this](EventLevel, const std::string& m) {
      std::lock_guard<std::mutex> lock(mutex);
      events.push_back(m);
    };
    r.gap_begin = [this](const Stamp&, const std::string&) {
      std::lock_guard<std::mutex> lock(mutex);
      ++gaps_begun;
    };
    r.gap_end = [this](const Stamp&) {
      std::lock_guard<std::mutex> lock(mutex);
      ++gaps_ended;
    };
    return r;
  }
};

inline SerialOptions Serial(const std::string& port) {
  SerialOptions s;
  s.port = port;
  s.baud = 115200;
  return s;
}

}  // namespace rk::capture
