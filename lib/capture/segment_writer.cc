#include "capture/segment_writer.h"

#include <sys/stat.h>
#include <unistd.h>

#include <cerrno>
#include <cmath>
#include <cstdio>
#include <cstring>
#include <filesystem>
#include <numeric>
#include <sstream>

#include "io/error.h"
#include "video/frame_source.h"

namespace rk::capture {
namespace fs = std::filesystem;

namespace {

std::string SegmentName(int index) {
  char b[32];
  std::snprintf(b, sizeof b, "seg_%03d", index);
  return b;
}

bool CheckFrame(const cv::Mat& frame, const FrameFormat& f, std::string* why) {
  const int type = f.bit_depth == 16 ? CV_16UC1 : CV_8UC1;
  if (frame.cols != f.width || frame.rows != f.height || frame.type() != type) {
    if (why) {
      *why = "frame is " + std::to_string(frame.cols) + "x" + std::to_string(frame.rows) +
             (frame.depth() == CV_16U ? " 16-bit" : " 8-bit") + " with " + std::to_string(frame.channels()) +
             " channel(s); the segment is " + std::to_string(f.width) + "x" + std::to_string(f.height) + " " +
             std::to_string(f.bit_depth) + "-bit mono";
    }
    return false;
  }
  return true;
}

class Y4mWriter : public SegmentWriter {
 public:
  Y4mWriter(std::string trial_dir, std::string camera, FrameFormat f, Syncer* syncer)
      : dir_(std::move(trial_dir)), camera_(std::move(camera)), f_(f), syncer_(syncer) {}
  ~Y4mWriter() override { End(); }

  std::string SegmentPath(int index) const override { return camera_ + "/" + SegmentName(index) + ".y4m"; }

  bool Begin(int index, std::string* why) override {
    End();
    const std::string path = (fs::path(dir_) / SegmentPath(index)).string();
    file_ = DurableFile::Create(path, true, why);
    if (!file_) return false;
    const std::string header = Y4mHeader(f_);
    if (!file_->Append(header, why)) {
      // Disk full before the first frame: leave no half header behind.
      file_.reset();
      ::unlink(path.c_str());
      return false;
    }
    if (syncer_) {
      syncer_->Add(file_);
      syncer_->DirectoryChanged((fs::path(dir_) / camera_).string());
    }
    frames_ = 0;
    open_ = true;
    return true;
  }

  bool Write(const cv::Mat& frame, std::string* why) override {
    if (!open_) {
      if (why) *why = "no segment open";
      return false;
    }
    if (!CheckFrame(frame, f_, why)) return false;
    static const char kMarker[] = "FRAME\n";
    const cv::Mat c = frame.isContinuous() ? frame : frame.clone();
    iovec parts[2];
    parts[0].iov_base = const_cast<char*>(kMarker);
    parts[0].iov_len = 6;
    parts[1].iov_base = c.data;
    parts[1].iov_len = c.total() * c.elemSize();
    last_start_ = file_->size();
    too_large_ = false;
    if (!file_->Append(parts, 2, why)) {
      too_large_ = file_->last_error() == EFBIG;
      return false;
    }
    file_->StartWriteback();
    ++frames_;
    return true;
  }

  bool UndoLast(std::string* why) override {
    if (!open_ || frames_ == 0) return true;
    if (!file_->TruncateTo(last_start_, why)) return false;
    --frames_;
    return true;
  }

  void End() override {
    if (file_) file_->Retire();
    file_.reset();
    open_ = false;
  }

 private:
  std::string dir_, camera_;
  FrameFormat f_;
  Syncer* syncer_;
  std::shared_ptr<DurableFile> file_;
  std::int64_t last_start_ = 0;
};

class PgmWriter : public SegmentWriter {
 public:
  PgmWriter(std::string trial_dir, std::string camera, FrameFormat f, Syncer* syncer)
      : dir_(std::move(trial_dir)), camera_(std::move(camera)), f_(f), syncer_(syncer) {
    header_ = "P5\n" + std::to_string(f_.width) + " " + std::to_string(f_.height) + "\n" +
              (f_.bit_depth == 16 ? "65535" : "255") + "\n";
  }

  std::string SegmentPath(int index) const override { return camera_ + "/" + SegmentName(index) + "/%06d.pgm"; }

  bool Begin(int index, std::string* why) override {
    End();
    folder_ = (fs::path(dir_) / camera_ / SegmentName(index)).string();
    if (::mkdir(folder_.c_str(), 0755) != 0) {
      if (why) *why = "cannot create " + folder_ + ": " + std::strerror(errno);
      return false;
    }
    if (syncer_) syncer_->DirectoryChanged((fs::path(dir_) / camera_).string());
    pattern_ = (fs::path(dir_) / SegmentPath(index)).string();
    frames_ = 0;
    open_ = true;
    return true;
  }

  bool Write(const cv::Mat& frame, std::string* why) override {
    if (!open_) {
      if (why) *why = "no segment open";
      return false;
    }
    if (!CheckFrame(frame, f_, why)) return false;
    const std::string final_path = video::SequenceFramePath(pattern_, frames_);
    const std::string tmp = (fs::path(folder_) / ("." + fs::path(final_path).filename().string() + ".tmp")).string();
    ::unlink(tmp.c_str());  // a leftover of an earlier failed attempt
    auto file = DurableFile::Create(tmp, true, why);
    if (!file) return false;
    const void* data = frame.data;
    std::size_t bytes = frame.total() * frame.elemSize();
    if (f_.bit_depth == 16 || !frame.isContinuous()) {
      // PGM stores 16-bit samples big-endian.
      if (f_.bit_depth == 16) {
        swapped_.create(frame.rows, frame.cols, CV_16UC1);
        for (int r = 0; r < frame.rows; ++r) {
          const std::uint16_t* s = frame.ptr<std::uint16_t>(r);
          std::uint16_t* d = swapped_.ptr<std::uint16_t>(r);
          for (int c = 0; c < frame.cols; ++c) d[c] = static_cast<std::uint16_t>((s[c] >> 8) | (s[c] << 8));
        }
      } else {
        frame.copyTo(swapped_);
      }
      data = swapped_.data;
      bytes = swapped_.total() * swapped_.elemSize();
    }
    iovec parts[2];
    parts[0].iov_base = header_.data();
    parts[0].iov_len = header_.size();
    parts[1].iov_base = const_cast<void*>(data);
    parts[1].iov_len = bytes;
    if (!file->Append(parts, 2, why)) {
      ::unlink(tmp.c_str());
      return false;
    }
    file->StartWriteback();
    if (std::rename(tmp.c_str(), final_path.c_str()) != 0) {
      if (why) *why = "cannot rename " + tmp + ": " + std::strerror(errno);
      ::unlink(tmp.c_str());
      return false;
    }
    file->Retire();
    if (syncer_) {
      syncer_->Add(file);
      syncer_->DirectoryChanged(folder_);
    }
    last_path_ = final_path;
    ++frames_;
    return true;
  }

  bool UndoLast(std::string* why) override {
    if (!open_ || frames_ == 0 || last_path_.empty()) return true;
    if (::unlink(last_path_.c_str()) != 0) {
      if (why) *why = "cannot remove " + last_path_ + ": " + std::strerror(errno);
      return false;
    }
    last_path_.clear();
    --frames_;
    return true;
  }

  void End() override { open_ = false; }

 private:
  std::string dir_, camera_;
  FrameFormat f_;
  Syncer* syncer_;
  std::string header_, folder_, pattern_, last_path_;
  cv::Mat swapped_;
};

}  // namespace

std::unique_ptr<SegmentWriter> MakeSegmentWriter(const std::string& format, const std::string& trial_dir,
                                                 const std::string& camera, const FrameFormat& frame_format,
                                                 Syncer* syncer) {
  if (format == "y4m") return std::make_unique<Y4mWriter>(trial_dir, camera, frame_format, syncer);
  if (format == "pgm") return std::make_unique<PgmWriter>(trial_dir, camera, frame_format, syncer);
  throw UsageError("video format must be 'y4m' or 'pgm', not '" + format + "'");
}

}  // namespace rk::capture
