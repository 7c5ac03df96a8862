// y4m header line and reader; see y4m.h.
#include "video/y4m.h"

#include <algorithm>
#include <cmath>
#include <cstring>
#include <fstream>
#include <numeric>
#include <sstream>

#include "io/error.h"
#include "io/run_record.h"

namespace rk::video {
namespace {

void FpsFraction(double fps, std::int64_t* num, std::int64_t* den) {
  // Exact for integer rates and for rates given to 3 decimals (29.97, 23.976).
  std::int64_t d = 1000;
  std::int64_t n = std::llround(fps * static_cast<double>(d));
  const std::int64_t g = std::gcd(n, d);
  *num = n / g;
  *den = d / g;
}

constexpr std::uint64_t kMaxHeaderLine = 1024;

}  // namespace

std::string Y4mHeader(const FrameFormat& f) {
  std::int64_t num = 0, den = 1;
  FpsFraction(f.fps, &num, &den);
  return "YUV4MPEG2 W" + std::to_string(f.width) + " H" + std::to_string(f.height) + " F" + std::to_string(num) +
         ":" + std::to_string(den) + " Ip A1:1 C" + (f.bit_depth == 16 ? "mono16" : "mono") + "\n";
}

bool ParseY4mHeader(const std::string& line, FrameFormat* f) {
  std::istringstream in(line);
  std::string magic;
  in >> magic;
  if (magic != "YUV4MPEG2") return false;
  FrameFormat out;
  bool have_w = false, have_h = false, have_c = false;
  std::string tok;
  while (in >> tok) {
    const char k = tok[0];
    const std::string v = tok.substr(1);
    try {
      if (k == 'W') {
        out.width = std::stoi(v);
        have_w = true;
      } else if (k == 'H') {
        out.height = std::stoi(v);
        have_h = true;
      } else if (k == 'F') {
        const auto colon = v.find(':');
        if (colon == std::string::npos) return false;
        const double num = std::stod(v.substr(0, colon)), den = std::stod(v.substr(colon + 1));
        if (!(num > 0 && den > 0)) return false;
        out.fps = num / den;
      } else if (k == 'C') {
        if (v == "mono") {
          out.bit_depth = 8;
        } else if (v == "mono16") {
          out.bit_depth = 16;
        } else {
          return false;
        }
        have_c = true;
      }
    } catch (const std::exception&) {
      return false;
    }
  }
  if (!have_w || !have_h || !have_c || out.width <= 0 || out.height <= 0) return false;
  *f = out;
  return true;
}

bool IsMonoY4m(const std::string& path) {
  std::ifstream in(path, std::ios::binary);
  std::string line;
  if (!in || !std::getline(in, line) || line.size() >= kMaxHeaderLine) return false;
  FrameFormat f;
  return ParseY4mHeader(line, &f);
}

Y4mReader::Y4mReader(const std::string& path) : file_(path) {
  const ByteView v = file_.view();
  const std::uint8_t* d = v.data();
  const std::uint64_t n = std::min<std::uint64_t>(v.size(), kMaxHeaderLine);
  const void* nl = n ? std::memchr(d, '\n', n) : nullptr;
  if (!nl) v.Fail(0, "no YUV4MPEG2 header line");
  const std::uint64_t len = static_cast<std::uint64_t>(static_cast<const std::uint8_t*>(nl) - d);
  if (!ParseY4mHeader(std::string(reinterpret_cast<const char*>(d), len), &format_)) {
    v.Fail(0, "not a mono YUV4MPEG2 header (C mono or C mono16 with W, H and F)");
  }
  pos_ = len + 1;
  frame_bytes_ = static_cast<std::uint64_t>(format_.width) * static_cast<std::uint64_t>(format_.height) *
                 (format_.bit_depth == 16 ? 2u : 1u);
}

bool Y4mReader::Read(cv::Mat* out) {
  const ByteView v = file_.view();
  if (pos_ >= v.size()) return false;
  // The FRAME line by pread too: touching the mapping would fault a page per frame.
  char line[kMaxHeaderLine];
  const std::uint64_t avail = std::min<std::uint64_t>(v.size() - pos_, kMaxHeaderLine);
  file_.ReadAt(pos_, std::min<std::uint64_t>(avail, 64), line, "FRAME line");
  const void* nl = std::memchr(line, '\n', std::min<std::uint64_t>(avail, 64));
  if (!nl && avail > 64) {  // FRAME parameters longer than 58 bytes: the whole line
    file_.ReadAt(pos_, avail, line, "FRAME line");
    nl = std::memchr(line, '\n', avail);
  }
  if (avail < 5 || std::memcmp(line, "FRAME", 5) != 0 || !nl) {
    v.Fail(pos_, "frame " + std::to_string(frames_read_) + " has no FRAME line (cut short or not a y4m frame)");
  }
  const std::uint64_t data = pos_ + static_cast<std::uint64_t>(static_cast<const char*>(nl) - line) + 1;
  if (data > v.size() || v.size() - data < frame_bytes_) {
    // A torn last frame (the recorder stopped mid-write): said, not read; `rk-capture recover` cuts it off.
    io::EmitWarning(v.file() + ": byte " + std::to_string(pos_) + ": frame " + std::to_string(frames_read_) +
                    " is cut short (" + std::to_string(v.size() - std::min(data, v.size())) + " of " +
                    std::to_string(frame_bytes_) + " bytes): a torn last frame, not read");
    pos_ = v.size();
    return false;
  }
  out->create(format_.height, format_.width, format_.bit_depth == 16 ? CV_16UC1 : CV_8UC1);
  // The samples straight into the frame (mono16 is little-endian, as the host): one copy, by the kernel.
  file_.ReadAt(data, frame_bytes_, out->data, "frame " + std::to_string(frames_read_));
  pos_ = data + frame_bytes_;
  ++frames_read_;
  return true;
}

}  // namespace rk::video
