// The capture reader of lib/asterix (ReadCaptureBuffer: libpcap over pcap/pcapng octets — link layers, IPv4,
// fragment reassembly, UDP — or a raw stream) with the record walker behind it. Promises checked: every datagram
// handed on fits a UDP payload (at most 65527 octets) and lies in readable memory (its octets are summed, so
// ASan sees every read); only input errors (rk::Error) may end a read.
#include <cstdint>
#include <cstdlib>

#include "asterix/block.h"
#include "asterix/capture.h"
#include "fuzz_util.h"

namespace {

struct Count : rk::asterix::BlockVisitor {
  std::size_t records = 0, bad = 0;
  void OnRecord(const rk::asterix::RecordLayout&, std::size_t) override { ++records; }
  void OnBad(std::size_t, std::uint8_t, const char*) override { ++bad; }
};

}  // namespace

extern "C" int LLVMFuzzerTestOneInput(const std::uint8_t* data, std::size_t size) {
  rk::fuzz::ExpectOnlyInputErrors([&] {
    rk::asterix::CaptureStats stats;
    Count count;
    volatile unsigned sum = 0;
    rk::asterix::ReadCaptureBuffer(
        data, size, "fuzz.pcap",
        [&](const rk::asterix::Datagram& d) {
          if (d.packet != 0 && d.size > 65527) std::abort();
          for (std::size_t i = 0; i < d.size; ++i) sum = sum + d.data[i];
          rk::asterix::WalkBlocks(d.data, d.size, &count);
        },
        [](std::uint64_t, const std::string& reason) {
          if (reason.empty()) std::abort();
        },
        &stats);
    if (stats.udp_datagrams > stats.packets) std::abort();
  });
  return 0;
}
