// Opening and decoding camera files; the parsers are in cine_file.cc and mraw_file.cc.
#include "video/camera_file.h"

#include <algorithm>
#include <exception>
#include <filesystem>
#include <opencv2/core/utility.hpp>
#include <opencv2/imgproc.hpp>

#include "io/error.h"

namespace rk::video {
namespace fs = std::filesystem;

const char* TimeSourceName(TimeSource source) {
  switch (source) {
    case TimeSource::kIrig: return "irig";
    case TimeSource::kCamera: return "camera";
    case TimeSource::kContainer: return "container";
    case TimeSource::kHost: return "host";
    case TimeSource::kNominal: return "nominal";
  }
  return "nominal";
}

namespace {

std::string LowerExtension(const std::string& path) {
  std::string e = fs::path(path).extension().string();
  for (char& c : e) c = static_cast<char>(std::tolower(static_cast<unsigned char>(c)));
  return e;
}

// The file beside `path` with the same stem and one of `extensions` (either case), "" if none.
std::string Sibling(const std::string& path, std::initializer_list<const char*> extensions) {
  for (const char* ext : extensions) {
    for (const std::string& e : {std::string(ext), [&] {
                                   std::string u(ext);
                                   for (char& c : u) c = static_cast<char>(std::toupper(static_cast<unsigned char>(c)));
                                   return u;
                                 }()}) {
      fs::path p(path);
      p.replace_extension(e);
      std::error_code ec;
      if (fs::exists(p, ec)) return p.string();
    }
  }
  return "";
}
}  // namespace

bool IsCameraFile(const std::string& path) {
  const std::string e = LowerExtension(path);
  return e == ".cine" || e == ".mraw" || e == ".cihx" || e == ".cih";
}

CameraFileReader::CameraFileReader(const std::string& path) {
  const std::string ext = LowerExtension(path);
  if (ext == ".cine") {
    data_ = std::make_unique<MappedFile>(path);
    file_ = ParseCine(data_->view());
  } else {
    std::string header = path, data = path;
    if (ext == ".mraw") {
      header = Sibling(path, {".cihx", ".cih"});
      if (header.empty()) throw IoError(path, "no .cihx or .cih of the same name beside it: its frame size and depth are there");
    } else {
      data = Sibling(path, {".mraw"});
      if (data.empty()) throw IoError(path, "no .mraw of the same name beside it");
    }
    header_ = std::make_unique<MappedFile>(header);
    data_ = std::make_unique<MappedFile>(data);
    const bool xml = LowerExtension(header) == ".cihx";
    file_ = xml ? ParseCihx(header_->view(), data, data_->size()) : ParseCih(header_->view(), data, data_->size());
  }
}

void CameraFileReader::Read(std::int64_t index, cv::Mat* out) {
  if (file_.bayer_to_gray < 0) {
    ReadMosaic(index, out);
    return;
  }
  ReadMosaic(index, &raw_);
  cv::cvtColor(raw_, *out, file_.bayer_to_gray);
}

void CameraFileReader::ReadMosaic(std::int64_t index, cv::Mat* out) {
  RK_CHECK(index >= 0 && index < frames(), "frame index out of range");
  const CameraFile& f = file_;
  const std::uint64_t offset = f.frame_offsets[static_cast<std::size_t>(index)];
  const std::string what = "frame " + std::to_string(index);
  const bool eight = f.packing == Packing::kU8;
  out->create(f.height, f.width, eight ? CV_8UC1 : CV_16UC1);
  const std::uint64_t width = static_cast<std::uint64_t>(f.width);
  const std::uint64_t pixels = width * static_cast<std::uint64_t>(f.height);
  if (!f.bottom_up && (eight || (f.packing == Packing::kU16LE && f.significant_bits == 16))) {
    data_->ReadAt(offset, f.frame_bytes, out->data, what);  // stored as delivered: straight into the frame
    return;
  }
  if (!f.bottom_up) {
    // Packed or widened: unpacked in place from the file's mapping (no copy out of the page cache: that copy
    // was 40 % of the time), in two bands, one per core (cv::parallel_for_, OpenCV's pool: no thread per frame).
    // bench/video_read_bench.sh: 1.6 x dd by pread into an L2-sized buffer, 1.0 x from the mapping.
    const std::uint8_t* const src = data_->MappedAt(offset, f.frame_bytes, what);
    const std::uint64_t group = static_cast<std::uint64_t>(InfoOf(f.packing).pixels_per_group);
    const std::uint64_t half = std::min(pixels, (pixels / 2 + group - 1) / group * group);  // whole groups
    std::uint64_t clamped[2] = {0, 0};
    std::exception_ptr error[2];  // rethrown here: OpenCV would turn them into cv::Exception
    cv::parallel_for_(cv::Range(0, 2), [&](const cv::Range& bands) {
      for (int b = bands.start; b < bands.end; ++b) try {
        const std::uint64_t begin = b == 0 ? 0 : half, end = b == 0 ? half : pixels;
        if (end > begin) {
          clamped[b] = Unpack16(f.packing, f.significant_bits, src + PackedBytes(f.packing, begin), end - begin,
                                out->ptr<std::uint16_t>() + begin);
        }
      } catch (...) {
        error[b] = std::current_exception();
      }
    });
    for (const std::exception_ptr& e : error) {
      if (e) std::rethrow_exception(e);
    }
    clamped_ += clamped[0] + clamped[1];
    return;
  }
  // Bottom-up (unpacked CINE): rows reversed through a buffer kept between frames.
  packed_.resize(f.frame_bytes);
  data_->ReadAt(offset, f.frame_bytes, packed_.data(), what);
  const std::uint64_t row_bytes = PackedBytes(f.packing, width);
  for (int r = 0; r < f.height; ++r) {
    const std::uint8_t* row = packed_.data() + static_cast<std::uint64_t>(f.height - 1 - r) * row_bytes;
    if (eight) {
      Unpack8(row, width, out->ptr<std::uint8_t>(r));
    } else {
      clamped_ += Unpack16(f.packing, f.significant_bits, row, width, out->ptr<std::uint16_t>(r));
    }
  }
}

}  // namespace rk::video
