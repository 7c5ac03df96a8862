// CaptureOptions' option table and checks (recorder.h).
#include "capture/recorder.h"

namespace rk::capture {

const io::OptionTable<CaptureOptions>& CaptureOptions::Table() {
  static const io::OptionTable<CaptureOptions> table = io::OptionTable<CaptureOptions>().Real(
      "--duration", &CaptureOptions::duration_s, "s", io::Bounds::AtLeast(0).Finite(),
      "Stop after S seconds (default: until SIGINT or SIGTERM)");
  return table;
}

bool CaptureOptions::Check(std::string* why) const {
  if (!Table().Check(*this, why)) return false;
  auto fail = [&](const std::string& w) {
    if (why) *why = w;
    return false;
  };
  if (out_dir.empty() || out_dir == "-") return fail("--out must name a folder");
  if (!(status_period_s > 0)) return fail("status period must be > 0");
  return true;
}

}  // namespace rk::capture
