// The recorder's serial devices: connect the rangefinder and turret, their rows from each sample (on the
// stamping thread, never waiting for the disk), and the stamping threads' real-time priority.
#include "capture/recorder_internal.h"

#include <algorithm>
#include <cmath>
#include <cstdlib>
#include <filesystem>

#include "io/error.h"

namespace rk::capture::internal {
namespace fs = std::filesystem;

void Recorder::Connect() {
  if (cfg_.rangefinder) {
    range_ = std::make_unique<DimetixDriver>(*cfg_.rangefinder, MakeReporter("range", &range_log_ptr_),
                                             [this](const RangeSample& s) { OnRange(s); });
    std::string why;
    if (!range_->Connect(&why)) throw IoError(cfg_.rangefinder->serial.port, "rangefinder: " + why);
  }
  if (cfg_.turret) {
    turret_ = std::make_unique<PtuDriver>(*cfg_.turret, MakeReporter("turret", &turret_log_ptr_),
                                          [this](const TurretSample& s) { OnTurret(s); });
    std::string why;
    if (!turret_->Connect(&why)) throw IoError(cfg_.turret->serial.port, "turret: " + why);
  }
  for (const CameraConfig& cc : cfg_.cameras) {
    auto cam = std::make_unique<CameraStream>();
    cam->cfg = cc;
    cam->folder = (fs::path(dir_) / cc.name).string();
    cam->src = MakeCameraSource(cc.source);
    std::string why;
    if (!cam->src->Open(&why)) throw IoError(cc.source_text, "camera '" + cc.name + "': " + why);
    cam->fps = cam->src->fps();
    if (std::abs(cam->fps - cc.source.fps) > 1e-6 * cc.source.fps) {
      Event(EventLevel::kWarning, "camera:" + cc.name,
            "runs at " + FormatFixed(cam->fps, 3) + " fps, not the configured " + FormatFixed(cc.source.fps, 3));
    }
    cam->frames_per_segment = std::max<std::int64_t>(1, std::llround(cfg_.segment_s * cam->fps));
    const int queue = cc.queue_frames > 0 ? cc.queue_frames : std::clamp(static_cast<int>(std::floor(cam->fps)), 2, 64);
    cam->pool.resize(static_cast<std::size_t>(queue));
    for (int i = 0; i < queue; ++i) cam->free_buffers.push_back(i);
    cameras_.push_back(std::move(cam));
    ReportFeatures(cameras_.back().get());
    Event(EventLevel::kInfo, "camera:" + cc.name,
          "opened " + cameras_.back()->src->kind() + " source '" + cc.source_text + "' at " +
              FormatFixed(cameras_.back()->fps, 3) + " fps, " + std::to_string(queue) + " frame buffers");
  }
}

void Recorder::ReportFeatures(CameraStream* cam) {
  const io::Json r = cam->src->StreamReport();
  if (!r.is_object() || !r.contains("features")) return;
  if (r.contains("ptp") && r["ptp"].is_object()) {
    const io::Json& p = r["ptp"];
    if (p.contains("error")) {
      Event(EventLevel::kWarning, "camera:" + cam->cfg.name, "IEEE 1588 asked for: " + p["error"].get<std::string>());
    } else {
      Event(EventLevel::kInfo, "camera:" + cam->cfg.name,
            "IEEE 1588: " + p.value("feature", "") + " = " + p.value("enabled", "") +
                (p.contains("status") ? ", status " + p["status"].get<std::string>() : ""));
    }
  }
  if (r.contains("trigger") && r["trigger"].is_object()) {
    const io::Json& t = r["trigger"];
    Event(EventLevel::kInfo, "camera:" + cam->cfg.name,
          "trigger " + t.value("selector", std::string("(no selector)")) + " " + t.value("mode", "") + " from " +
              t.value("source", std::string("(no source)")) + ": the frame's time is the " + t.value("frame_time", ""));
  }
  if (r.contains("receive_thread") && r["receive_thread"].is_string()) {
    Event(EventLevel::kInfo, "camera:" + cam->cfg.name, "stream receive thread: " + r["receive_thread"].get<std::string>());
  }
  for (const io::Json& f : r["features"]) {
    const std::string name = f.value("name", ""), asked = f.value("asked", ""), got = f.value("got", "");
    if (f.contains("error")) {
      Event(EventLevel::kWarning, "camera:" + cam->cfg.name,
            "feature " + name + " = " + asked + " refused: " + f["error"].get<std::string>() + " (reads " + got + ")");
    } else if (got != asked) {
      // A number the camera rounded reads back as its own text: the same value in other digits is no change.
      char* end = nullptr;
      const double a = std::strtod(asked.c_str(), &end);
      const bool a_num = end && *end == '\0' && !asked.empty();
      const double g = std::strtod(got.c_str(), &end);
      const bool g_num = end && *end == '\0' && !got.empty();
      if (!(a_num && g_num && a == g)) {
        Event(EventLevel::kWarning, "camera:" + cam->cfg.name, "feature " + name + " asked " + asked + ", got " + got);
      }
    } else {
      Event(EventLevel::kInfo, "camera:" + cam->cfg.name, "feature " + name + " = " + got);
    }
  }
}

void Recorder::OnRange(const RangeSample& s) {
  const double t = T(s.stamp) - cfg_.rangefinder->latency_s;
  std::string row = FormatFixed(t, 9) + ",";
  if (s.distance_01mm) row += FormatFixed(static_cast<double>(*s.distance_01mm) / 10000.0, 4);
  row += "," + std::to_string(s.status) + "," + FormatFixed(static_cast<double>(s.stamp.mono_ns) * 1e-9, 9) + "," +
         FormatFixed(static_cast<double>(s.stamp.real_ns) * 1e-9, 6);
  range_log_->Post(std::move(row));  // never wait for the disk on the stamping thread
}

void Recorder::OnTurret(const TurretSample& s) {
  const auto& o = *cfg_.turret;
  const double t = T(s.stamp) - o.latency_s;
  const double az = o.map.AzimuthDeg(s.pan_pos, s.pan_res_arcsec);
  const double el = o.map.ElevationDeg(s.tilt_pos, s.tilt_res_arcsec);
  const bool el_ok = el >= -90.0 && el <= 90.0;
  if (!el_ok && !el_warned_.exchange(true)) {
    Event(EventLevel::kWarning, "turret",
          "elevation " + FormatFixed(el, 3) + " deg outside [-90, 90]: check tilt_zero_deg / tilt_sign; such rows "
          "have empty angles");
  }
  std::string row = FormatFixed(t, 9) + "," + (el_ok ? FormatFixed(az, 9) : "") + "," +
                    (el_ok ? FormatFixed(el, 9) : "") + "," + std::to_string(s.pan_pos) + "," +
                    std::to_string(s.tilt_pos) + "," + FormatFixed(s.pan_res_arcsec, 6) + "," +
                    FormatFixed(s.tilt_res_arcsec, 6) + "," + FormatFixed(s.pair_dt_s, 6) + "," +
                    FormatFixed(static_cast<double>(s.stamp.mono_ns) * 1e-9, 9) + "," +
                    FormatFixed(static_cast<double>(s.stamp.real_ns) * 1e-9, 6);
  if (el_ok) {
    last_az_ = az;
    last_el_ = el;
  }
  turret_log_->Post(std::move(row));
}

void Recorder::RealTime(const std::string& stream) {
  if (cfg_.realtime_priority <= 0) return;
  std::string why;
  if (RaiseThreadPriority(cfg_.realtime_priority, &why)) {
    ++realtime_threads_;
  } else {
    ++normal_threads_;
    if (!realtime_warned_.exchange(true)) {
      Event(EventLevel::kInfo, stream,
            "real-time priority " + std::to_string(cfg_.realtime_priority) + " not granted (" + why +
                "): arrival stamps may be late while the CPUs are busy");
    }
  }
}

}  // namespace rk::capture::internal
