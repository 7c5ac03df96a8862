// The ASTERIX record walker of lib/asterix (WalkBlocks over the UAP tables, then DecodeTargetReport /
// DecodeServiceMessage): any octets as one datagram. Promises checked: every record and every item lies inside
// the buffer, records follow each other without overlap, every problem's offset is inside the buffer, and the
// decoded values stay in their items' ranges. No exception is allowed at all (the walker reports, never throws).
#include <cmath>
#include <cstdint>
#include <cstdlib>

#include "asterix/block.h"

namespace {

struct Check : rk::asterix::BlockVisitor {
  std::size_t size = 0, next = 0;
  void OnRecord(const rk::asterix::RecordLayout& r, std::size_t offset) override {
    if (offset < next || offset + r.size > size || r.size == 0) std::abort();
    next = offset + r.size;
    for (const rk::asterix::ItemRef& i : r.items) {
      if (i.size != 0 && std::size_t{i.offset} + i.size > r.size) std::abort();
    }
    if (r.category->category == 34) {
      const rk::asterix::ServiceMessage m = rk::asterix::DecodeServiceMessage(r);
      if (m.time_of_day_s >= 131072.0 || m.sector_deg >= 360.0) std::abort();
    } else {
      const rk::asterix::TargetReport t = rk::asterix::DecodeTargetReport(r);
      if (t.rho_m < 0 || t.rho_m > 512 * 1852.0 || t.theta_deg < 0 || t.theta_deg >= 360.0) std::abort();
      if (std::abs(t.flight_level) > 2048 || (t.mode3a > 07777)) std::abort();
    }
  }
  void OnBad(std::size_t offset, std::uint8_t, const char* reason) override {
    if (offset > size || reason == nullptr || reason[0] == '\0') std::abort();
  }
};

}  // namespace

extern "C" int LLVMFuzzerTestOneInput(const std::uint8_t* data, std::size_t size) {
  Check c;
  c.size = size;
  rk::asterix::WalkBlocks(data, size, &c);
  return 0;
}
