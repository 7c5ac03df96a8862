#include "io/progress.h"

#include <algorithm>
#include <chrono>
#include <cmath>
#include <cstdio>
#include <cstdlib>
#include <iostream>

namespace rk::io {

namespace {

double SteadySeconds() {
  return std::chrono::duration<double>(std::chrono::steady_clock::now().time_since_epoch()).count();
}

std::string FormatDuration(double s) {
  const auto total = static_cast<std::int64_t>(std::llround(std::max(0.0, s)));
  const std::int64_t h = total / 3600, m = (total / 60) % 60, sec = total % 60;
  char buf[32];
  if (h > 0) {
    std::snprintf(buf, sizeof buf, "%lld:%02lld:%02lld", static_cast<long long>(h), static_cast<long long>(m),
                  static_cast<long long>(sec));
  } else {
    std::snprintf(buf, sizeof buf, "%lld:%02lld", static_cast<long long>(m), static_cast<long long>(sec));
  }
  return buf;
}

}  // namespace

std::string FormatProgress(const std::string& tool, const std::string& unit, std::int64_t done, std::int64_t total,
                           double elapsed_s) {
  std::string line = tool + ": " + std::to_string(done);
  if (total > 0) {
    line += "/" + std::to_string(total) + " " + unit + " (" + std::to_string(100 * std::min(done, total) / total) + "%)";
  } else {
    line += " " + unit;
  }
  const double rate = elapsed_s > 0 ? static_cast<double>(done) / elapsed_s : 0.0;
  if (rate > 0) {
    char buf[32];
    std::snprintf(buf, sizeof buf, rate >= 10 ? "%.0f" : "%.1f", rate);
    line += std::string(", ") + buf + "/s";
    if (total > 0 && done < total) line += ", ETA " + FormatDuration(static_cast<double>(total - done) / rate);
  }
  return line;
}

ProgressMeter::ProgressMeter(std::string tool, std::string unit, std::int64_t total, bool enabled)
    : tool_(std::move(tool)), unit_(std::move(unit)), total_(total), enabled_(enabled), start_s_(SteadySeconds()) {
  if (const char* f = std::getenv(kProgressFileEnv)) progress_file_ = f;
}

void ProgressMeter::Update(std::int64_t done) {
  if (!enabled_ && progress_file_.empty()) return;
  const double now = SteadySeconds();
  if (last_draw_s_ >= 0 && now - last_draw_s_ < 1.0 / kRedrawsPerSecond && !(total_ > 0 && done >= total_)) return;
  last_draw_s_ = now;
  if (!progress_file_.empty()) {
    // Rewritten in place, one short line: the reader takes whatever complete line it finds.
    if (std::FILE* f = std::fopen(progress_file_.c_str(), "w")) {
      std::fprintf(f, "%lld %lld %s\n", static_cast<long long>(done), static_cast<long long>(total_), unit_.c_str());
      std::fclose(f);
    }
  }
  if (!enabled_) return;
  drawn_ = true;
  // \r and erase to the end of the line (ANSI EL): a shorter line leaves nothing behind.
  std::cerr << "\r" << FormatProgress(tool_, unit_, done, total_, now - start_s_) << "\x1b[K" << std::flush;
}

void ProgressMeter::Finish() {
  if (enabled_ && drawn_) std::cerr << "\r\x1b[K" << std::flush;
  drawn_ = false;
}

}  // namespace rk::io
