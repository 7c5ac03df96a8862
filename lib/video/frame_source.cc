#include "video/frame_source.h"

#include <sys/wait.h>
#include <unistd.h>

#include <cstdlib>
#include <filesystem>
#include <fstream>
#include <opencv2/imgcodecs.hpp>  // the flags only: the functions come from video/image_codecs.h
#include <opencv2/imgproc.hpp>
#include <sstream>

#include "io/error.h"
#include "io/run_record.h"
#include "video/camera_file.h"
#include "video/image_codecs.h"
#include "video/y4m.h"
#include "video/stdin_video.h"

namespace rk::video {
namespace fs = std::filesystem;

std::string ShellQuote(const std::string& s) {
  std::string out = "'";
  for (char c : s) {
    if (c == '\'') {
      out += "'\\''";
    } else {
      out.push_back(c);
    }
  }
  out.push_back('\'');
  return out;
}

bool IsSequencePattern(const std::string& path) {
  auto p = path.find('%');
  if (p == std::string::npos) return false;
  auto d = path.find('d', p);
  return d != std::string::npos;
}

namespace {

std::string ReadSmallFile(const std::string& path) {
  std::ifstream in(path);
  std::stringstream ss;
  ss << in.rdbuf();
  return ss.str();
}

std::string FirstLine(const std::string& s) {
  auto e = s.find('\n');
  return e == std::string::npos ? s : s.substr(0, e);
}

// cv::imread, with OpenCV's own refusals (cv::Exception, e.g. a header promising a frame beyond
// CV_IO_MAX_IMAGE_HEIGHT) turned into the DataError a file that cannot be decoded gets.
cv::Mat ReadImage(const std::string& path) {
  try {
    return ImRead(path, cv::IMREAD_UNCHANGED);
  } catch (const cv::Exception& e) {
    throw DataError(path, 0, 0, "cannot decode image (" + e.err + ")");
  }
}

void CheckReadable(const std::string& path) {
  std::error_code ec;
  if (!fs::exists(path, ec)) throw IoError(path, "no such file");
  if (fs::is_directory(path, ec)) throw IoError(path, "is a folder; give a video file or a pattern like dir/%06d.png");
  std::ifstream in(path);
  if (!in) throw IoError(path, "cannot open for reading");
}

}  // namespace

std::string SequenceFramePath(const std::string& pattern, std::int64_t index) {
  // "%06d" → "%06lld" so the 64-bit index is passed with a matching conversion.
  auto p = pattern.find('%');
  auto d = pattern.find('d', p);
  const std::string fmt = pattern.substr(0, d) + "lld" + pattern.substr(d + 1);
  std::vector<char> buf(pattern.size() + 64);
  std::snprintf(buf.data(), buf.size(), fmt.c_str(), static_cast<long long>(index));
  return std::string(buf.data());
}

std::string MakeTempFile() {
  const char* tmp = std::getenv("TMPDIR");
  std::string templ = std::string(tmp && *tmp ? tmp : "/tmp") + "/rk-ffmpeg-XXXXXX";
  std::vector<char> buf(templ.begin(), templ.end());
  buf.push_back('\0');
  int fd = mkstemp(buf.data());
  if (fd < 0) throw IoError(templ, "cannot create a temporary file");
  ::close(fd);
  return buf.data();
}

void RefuseStdinVideo(const std::vector<std::string>& paths, const std::string& option) {
  for (const std::string& p : paths) {
    if (p != "-") continue;
    throw UsageError(option + " -: a video cannot be read from stdin (it is probed with ffprobe, then decoded "
                     "with ffmpeg, from a file); save the stream first, e.g. ffmpeg -i pipe:0 -c copy video.mkv, "
                     "and give that file");
  }
}

VideoInfo ProbeVideo(const std::string& path) {
  RefuseStdinVideo({path});
  if (IsSequencePattern(path)) {
    for (std::int64_t start : {0, 1}) {
      std::string first = SequenceFramePath(path, start);
      if (fs::exists(first)) {
        cv::Mat img = ReadImage(first);
        if (img.empty()) throw DataError(first, 0, 0, "cannot decode image");
        return {img.cols, img.rows, img.depth() == CV_16U ? 16 : 8};
      }
    }
    throw IoError(path, "no image matches the pattern (tried numbering from 0 and 1)");
  }
  CheckReadable(path);
  if (IsCameraFile(path)) {
    CameraFileReader reader(path);
    return {reader.file().width, reader.file().height, reader.file().packing == Packing::kU8 ? 8 : 16};
  }
  if (IsMonoY4m(path)) {
    const Y4mReader reader(path);
    return {reader.format().width, reader.format().height, reader.format().bit_depth};
  }
  std::string err = MakeTempFile();
  std::string cmd = "ffprobe -v error -select_streams v:0 -show_entries stream=width,height,pix_fmt -of csv=p=0 " +
                    ShellQuote(path) + " 2>" + ShellQuote(err);
  FILE* p = ::popen(cmd.c_str(), "r");
  if (!p) throw IoError(path, "cannot run ffprobe");
  char line[512] = {0};
  std::string out;
  while (std::fgets(line, sizeof line, p)) out += line;
  int rc = ::pclose(p);
  std::string errtext = ReadSmallFile(err);
  ::unlink(err.c_str());
  if (rc != 0 || out.empty()) {
    throw DataError(path, 0, 0,
                    "not a readable video" + (errtext.empty() ? std::string() : ": " + FirstLine(errtext)));
  }
  // "2448,2048,gray"
  VideoInfo info;
  std::string pix;
  std::stringstream ss(FirstLine(out));
  std::string w, h;
  std::getline(ss, w, ',');
  std::getline(ss, h, ',');
  std::getline(ss, pix, ',');
  info.width = std::atoi(w.c_str());
  info.height = std::atoi(h.c_str());
  if (info.width <= 0 || info.height <= 0) throw DataError(path, 0, 0, "video has no frame size");
  // Anything deeper than 8 bits per sample is delivered as 16-bit.
  bool deep = pix.find("16") != std::string::npos || pix.find("12") != std::string::npos ||
              pix.find("10") != std::string::npos || pix.find("14") != std::string::npos;
  info.bit_depth = deep ? 16 : 8;
  return info;
}

FrameSource::FrameSource(std::vector<std::string> segments) : segments_(std::move(segments)) {
  if (segments_.empty()) throw UsageError("no video given");
  RefuseStdinVideo(segments_);
  // Fail early on paths that do not exist.
  for (const auto& s : segments_) {
    if (!IsSequencePattern(s)) CheckReadable(s);
  }
}

FrameSource::~FrameSource() {
  camera_.reset();
  y4m_.reset();
  if (pipe_) {
    ::pclose(pipe_);
    pipe_ = nullptr;
  }
  if (!stderr_path_.empty()) ::unlink(stderr_path_.c_str());
}

VideoInfo FrameSource::info() {
  if (!have_info_) {
    info_ = ProbeVideo(segments_.front());
    have_info_ = true;
  }
  return info_;
}

bool FrameSource::OpenNext() {
  if (next_segment_ >= segments_.size()) return false;
  current_ = segments_[next_segment_++];
  segment_frames_ = 0;
  camera_.reset();
  y4m_.reset();
  VideoInfo seg;
  is_sequence_ = IsSequencePattern(current_);
  if (!is_sequence_ && IsCameraFile(current_)) {
    camera_ = std::make_unique<CameraFileReader>(current_);
    camera_next_ = 0;
    seg = {camera_->file().width, camera_->file().height, camera_->file().packing == Packing::kU8 ? 8 : 16};
  } else if (!is_sequence_ && IsMonoY4m(current_)) {
    y4m_ = std::make_unique<Y4mReader>(current_);
    seg = {y4m_->format().width, y4m_->format().height, y4m_->format().bit_depth};
  } else {
    seg = ProbeVideo(current_);
  }
  {
    std::error_code ec;
    const bool regular = fs::is_regular_file(current_, ec);
    const std::uintmax_t size = regular ? fs::file_size(current_, ec) : 0;
    io::RecordInputRead(current_, regular && !ec ? std::optional<std::uintmax_t>(size) : std::nullopt);
  }
  if (!have_info_) {
    info_ = seg;
    have_info_ = true;
  } else if (seg.width != info_.width || seg.height != info_.height || seg.bit_depth != info_.bit_depth) {
    throw DataError(current_, 0, 0, "segment differs in frame size or bit depth from the first segment");
  }
  buffer_.create(info_.height, info_.width, info_.bit_depth == 16 ? CV_16UC1 : CV_8UC1);
  if (camera_ || y4m_) return true;
  if (is_sequence_) {
    seq_index_ = fs::exists(SequenceFramePath(current_, 0)) ? 0 : 1;
    return true;
  }
  stderr_path_ = MakeTempFile();
  const char* fmt = info_.bit_depth == 16 ? "gray16le" : "gray";
  std::string cmd = "ffmpeg -v error -nostdin -i " + ShellQuote(current_) + " -map 0:v:0 -f rawvideo -pix_fmt " +
                    fmt + " - 2>" + ShellQuote(stderr_path_);
  pipe_ = ::popen(cmd.c_str(), "r");
  if (!pipe_) throw IoError(current_, "cannot run ffmpeg");
  return true;
}

void FrameSource::CloseCurrent(bool at_eof) {
  if (pipe_) {
    int rc = ::pclose(pipe_);
    pipe_ = nullptr;
    std::string errtext = ReadSmallFile(stderr_path_);
    ::unlink(stderr_path_.c_str());
    stderr_path_.clear();
    if (at_eof && (rc != 0 || !errtext.empty())) {
      throw DataError(current_, 0, 0,
                      "video is truncated or corrupt after " + std::to_string(segment_frames_) +
                          " frames (ffmpeg: " + FirstLine(errtext.empty() ? "exit status " + std::to_string(rc)
                                                                           : errtext) +
                          ")");
    }
  }
}

bool FrameSource::ReadFromPipe(cv::Mat* frame) {
  const std::size_t bytes = buffer_.total() * buffer_.elemSize();
  std::size_t got = std::fread(buffer_.data, 1, bytes, pipe_);
  if (got == bytes) {
    *frame = buffer_;
    return true;
  }
  if (got != 0) {
    CloseCurrent(false);
    throw DataError(current_, 0, 0,
                    "video is truncated: frame " + std::to_string(segment_frames_) + " of this segment is incomplete");
  }
  CloseCurrent(true);
  return false;
}

bool FrameSource::ReadFromSequence(cv::Mat* frame) {
  std::string path = SequenceFramePath(current_, seq_index_);
  if (!fs::exists(path)) return false;
  cv::Mat img = ReadImage(path);
  if (img.empty()) throw DataError(path, 0, 0, "cannot decode image (truncated or not an image)");
  if (img.channels() == 3) cv::cvtColor(img, img, cv::COLOR_BGR2GRAY);
  if (img.channels() == 4) cv::cvtColor(img, img, cv::COLOR_BGRA2GRAY);
  if (img.cols != info_.width || img.rows != info_.height) {
    throw DataError(path, 0, 0, "image size differs from the first frame");
  }
  if ((img.depth() == CV_16U) != (info_.bit_depth == 16)) throw DataError(path, 0, 0, "image bit depth differs");
  ++seq_index_;
  *frame = img;
  return true;
}

bool FrameSource::ReadFromCamera(cv::Mat* frame) {
  if (y4m_) {
    if (!y4m_->Read(&buffer_)) return false;
    *frame = buffer_;
    return true;
  }
  if (camera_next_ >= camera_->frames()) return false;
  camera_->Read(camera_next_++, &buffer_);
  *frame = buffer_;
  return true;
}

bool FrameSource::Read(cv::Mat* frame) {
  while (true) {
    const bool in_process = camera_ || y4m_;
    if (current_.empty() || (!is_sequence_ && !pipe_ && !in_process)) {
      if (!OpenNext()) return false;
    }
    bool ok = (camera_ || y4m_) ? ReadFromCamera(frame) : is_sequence_ ? ReadFromSequence(frame) : ReadFromPipe(frame);
    if (ok) {
      ++frames_read_;
      ++segment_frames_;
      return true;
    }
    // End of this segment: move on.
    if (is_sequence_) {
      if (segment_frames_ == 0) throw IoError(current_, "no image matches the pattern");
      is_sequence_ = false;
    } else if (camera_ || y4m_) {
      camera_.reset();
      y4m_.reset();
      if (segment_frames_ == 0) throw DataError(current_, 0, 0, "video has no frames");
    } else if (segment_frames_ == 0) {
      throw DataError(current_, 0, 0, "video has no frames");
    }
    current_.clear();
    if (next_segment_ >= segments_.size()) return false;
  }
}

}  // namespace rk::video
