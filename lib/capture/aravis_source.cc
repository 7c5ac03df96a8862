// "aravis:<id>" camera source (SPEC.md §6): a GigE Vision or USB3 Vision camera through Aravis' own API
// (Debian libaravis-dev 0.8), with the camera's own clock; see camera_source.h and docs/rk-capture.md.
//
// Open: arv_camera_new(id) (an id as arv-tool-0.8 lists it, or an address); the station config's "features" set
// through GenICam in the order the file gives them (arv_gc_feature_node_set_value_from_string: the camera's own
// node decides the type) and each read back (asked, got: a refused or rounded value is kept for the report and
// said by the recorder); continuous acquisition; on a GigE camera the packet size negotiated
// (arv_camera_gv_auto_packet_size) and the stream's socket buffer sized for a whole frame; a pool of buffers of
// one payload each, a second's worth (at least 8).
// Grab: the next buffer (1 s timeout per wait, so that a stop is seen; kMaxSilenceS without a frame is an
// error, on which the recorder closes and reopens: the same features are set again). A buffer that is not
// complete (missing packets, timeout, size mismatch) is never returned as a frame: it is counted and given back.
// The frame's camera time stamp (arv_buffer_get_timestamp, ns on the camera's clock) is kept for frames.csv;
// the 16-bit GVSP frame ids (1..65535, then 1 again) count the frames the camera sent that never arrived.
// Pixel formats: Mono8 (8-bit); Mono10/12/16 and the packed Mono10p/12p/10Packed/12Packed as 16-bit, deep
// samples scaled to 16 bits by bit replication (lib/video/packed_pixels.h, as a camera file's are).
#include "capture/aravis_source.h"

#include <arv.h>

#include <pthread.h>
#include <sched.h>
#include <sys/resource.h>
#include <unistd.h>

#include <algorithm>
#include <cerrno>
#include <cmath>
#include <cstdlib>
#include <cstring>

#include "io/error.h"
#include "video/packed_pixels.h"

namespace rk::capture {
namespace {

constexpr guint64 kPopTimeoutUs = 1000000;  // one wait for a buffer (a stop is seen within it)
constexpr double kMaxSilenceS = 3.0;        // no frame for this long: the camera is gone
constexpr int kMinBuffers = 8;
constexpr std::uint64_t kFrameIdWrap = 65535;  // GVSP block ids run 1..65535
// The stream's receive thread: a low real-time priority (above every normal thread, below the kernel's own
// threaded interrupts at 50), else this nice level.
constexpr int kReceiveFifoPriority = 10;
constexpr int kReceiveNice = -10;

// The mono pixel formats recorded (PFNC / GigE Vision codes; Aravis 0.8's headers lack the PFNC packed
// Mono10p 0x010a0046 and Mono12p 0x010c0047) and their packing in lib/video (the one owner of unpacking).
struct Mono {
  std::uint32_t code;
  video::Packing packing;
  int bits;
};
constexpr Mono kMono[] = {
    {0x01080001u, video::Packing::kU8, 8},       // Mono8
    {0x01100003u, video::Packing::kU16LE, 10},   // Mono10 (in 16 bits)
    {0x01100005u, video::Packing::kU16LE, 12},   // Mono12 (in 16 bits)
    {0x01100007u, video::Packing::kU16LE, 16},   // Mono16
    {0x010a0046u, video::Packing::kP10LSB, 10},  // Mono10p
    {0x010c0047u, video::Packing::kP12LSB, 12},  // Mono12p
    {0x010c0004u, video::Packing::kP10GEV, 10},  // Mono10Packed
    {0x010c0006u, video::Packing::kP12GEV, 12},  // Mono12Packed
};
const Mono* FindMono(std::uint32_t code) {
  for (const Mono& m : kMono) {
    if (m.code == code) return &m;
  }
  return nullptr;
}

std::string TakeError(GError** e) {
  if (!*e) return "";
  std::string m = (*e)->message ? (*e)->message : "unknown error";
  g_clear_error(e);
  return m;
}

}  // namespace

TriggerTiming DecideTrigger(const std::function<std::optional<std::string>(const char*)>& get) {
  TriggerTiming t;
  const std::optional<std::string> mode = get("TriggerMode");
  if (!mode || *mode != "On") return t;
  const std::optional<std::string> selector = get("TriggerSelector");
  const std::optional<std::string> source = get("TriggerSource");
  t.report = {{"mode", *mode}};
  if (selector) t.report["selector"] = *selector;
  if (source) t.report["source"] = *source;
  // Each frame has a trigger of its own only for FrameStart (ExposureStart); an AcquisitionStart or
  // FrameBurstStart trigger starts frames the camera then times itself.
  if (selector && *selector != "FrameStart" && *selector != "ExposureStart") {
    t.report["frame_time"] = "camera stamp (the " + *selector + " trigger does not start each frame)";
    return t;
  }
  if (!source || source->rfind("Software", 0) == 0) {
    t.report["frame_time"] = "camera stamp (a software trigger has no time of its own)";
    return t;
  }
  t.hardware = true;
  for (const char* name : {"TriggerDelay", "TriggerDelayAbs"}) {
    const std::optional<std::string> v = get(name);
    if (!v) continue;
    char* end = nullptr;
    const double us = std::strtod(v->c_str(), &end);
    if (end == v->c_str() || *end != '\0' || !std::isfinite(us) || us < 0.0 || us > 1e9) continue;
    t.delay_ns = std::llround(us * 1e3);
    t.report["delay_feature"] = name;
    t.report["delay_s"] = us * 1e-6;
    t.report["frame_time"] = std::string("trigger: camera stamp - ") + name;
    return t;
  }
  t.report["delay_s"] = 0.0;
  t.report["frame_time"] = "trigger: camera stamp (the camera has no TriggerDelay: taken as 0)";
  return t;
}

struct AravisSource::Impl {
  ArvCamera* camera = nullptr;
  ArvStream* stream = nullptr;
  std::int64_t last_frame_ns = 0;  // monotonic time of the last frame (silence)
  std::uint64_t last_id = 0;
  bool have_id = false;
};

AravisSource::AravisSource(CameraSourceOptions o) : o_(std::move(o)), impl_(std::make_unique<Impl>()) {
  id_ = o_.source.substr(std::strlen("aravis:"));
}

AravisSource::~AravisSource() { Close(); }

void AravisSource::Close() {
  if (impl_->camera) {
    GError* e = nullptr;
    arv_camera_stop_acquisition(impl_->camera, &e);
    g_clear_error(&e);
  }
  if (impl_->stream) g_object_unref(impl_->stream);
  if (impl_->camera) g_object_unref(impl_->camera);
  impl_->stream = nullptr;
  impl_->camera = nullptr;
}

bool AravisSource::Open(std::string* why) {
  Close();
  GError* e = nullptr;
  impl_->camera = arv_camera_new(id_.c_str(), &e);
  if (!impl_->camera) {
    *why = "Aravis camera '" + id_ + "' not found or not answering" + (e ? ": " + TakeError(&e) : "");
    return false;
  }
  ArvDevice* dev = arv_camera_get_device(impl_->camera);
  features_.clear();
  for (const auto& [name, value] : o_.features) {
    FeatureResult f{name, value, "", ""};
    ArvGcNode* node = arv_device_get_feature(dev, name.c_str());
    if (!node || !ARV_IS_GC_FEATURE_NODE(node)) {
      f.error = "the camera has no feature '" + name + "'";
    } else {
      arv_gc_feature_node_set_value_from_string(ARV_GC_FEATURE_NODE(node), value.c_str(), &e);
      f.error = TakeError(&e);
      const char* got = arv_gc_feature_node_get_value_as_string(ARV_GC_FEATURE_NODE(node), &e);
      if (got) f.got = got;
      const std::string read_error = TakeError(&e);
      if (f.error.empty() && !read_error.empty()) f.error = "read back: " + read_error;
    }
    features_.push_back(f);
  }
  if (o_.ptp) EnablePtp();
  trigger_ = DecideTrigger([dev](const char* name) -> std::optional<std::string> {
    ArvGcNode* node = arv_device_get_feature(dev, name);
    if (!node || !ARV_IS_GC_FEATURE_NODE(node)) return std::nullopt;
    GError* err = nullptr;
    const char* v = arv_gc_feature_node_get_value_as_string(ARV_GC_FEATURE_NODE(node), &err);
    const bool ok = v && !err;
    g_clear_error(&err);
    if (!ok) return std::nullopt;
    return std::string(v);
  });
  arv_camera_set_acquisition_mode(impl_->camera, ARV_ACQUISITION_MODE_CONTINUOUS, &e);
  g_clear_error(&e);
  gv_ = arv_camera_is_gv_device(impl_->camera);
  if (gv_) {
    packet_size_ = static_cast<int>(arv_camera_gv_auto_packet_size(impl_->camera, &e));
    g_clear_error(&e);
  }
  double rate = arv_camera_get_frame_rate(impl_->camera, &e);
  if (e || !(rate > 0.0) || rate > 1e5) rate = o_.fps;
  g_clear_error(&e);
  fps_ = rate;
  const guint payload = arv_camera_get_payload(impl_->camera, &e);
  if (e || payload == 0) {
    *why = "Aravis camera '" + id_ + "': no payload size" + (e ? ": " + TakeError(&e) : "");
    Close();
    return false;
  }
  RaiseForReceiveThread();
  impl_->stream = arv_camera_create_stream(impl_->camera, nullptr, nullptr, &e);
  RestoreAfterReceiveThread();
  if (!impl_->stream) {
    *why = "Aravis camera '" + id_ + "': cannot open its stream: " + TakeError(&e);
    Close();
    return false;
  }
  if (gv_) {
    // A frame arrives as one burst of packets: a socket buffer that holds it, and resends where the camera
    // supports them.
    g_object_set(impl_->stream, "socket-buffer", ARV_GV_STREAM_SOCKET_BUFFER_AUTO, "packet-resend",
                 ARV_GV_STREAM_PACKET_RESEND_ALWAYS, nullptr);
  }
  const int n = std::max(kMinBuffers, static_cast<int>(std::ceil(fps_)));
  for (int i = 0; i < n; ++i) arv_stream_push_buffer(impl_->stream, arv_buffer_new_allocate(payload));
  arv_camera_start_acquisition(impl_->camera, &e);
  if (e) {
    *why = "Aravis camera '" + id_ + "': cannot start acquisition: " + TakeError(&e);
    Close();
    return false;
  }
  impl_->last_frame_ns = MonoNowNs();
  impl_->have_id = false;
  ++opens_;
  return true;
}

GrabResult AravisSource::Grab(cv::Mat* out, Stamp* at, std::string* why, const std::atomic<bool>& stop) {
  if (!impl_->stream) {
    *why = "Aravis camera '" + id_ + "' is not open";
    return GrabResult::kError;
  }
  while (!stop.load()) {
    ArvBuffer* b = arv_stream_timeout_pop_buffer(impl_->stream, kPopTimeoutUs);
    if (!b) {
      if (static_cast<double>(MonoNowNs() - impl_->last_frame_ns) * 1e-9 > kMaxSilenceS) {
        ++stats_.timeouts;
        *why = "Aravis camera '" + id_ + "' sent no frame for " + std::to_string(static_cast<int>(kMaxSilenceS)) + " s";
        return GrabResult::kError;
      }
      continue;
    }
    *at = Now();
    // The host's arrival is the frame's first packet's (Aravis' system time stamp, real-time clock), not this
    // pop: the monotonic reading moved back by as much, when the two agree within a second.
    const std::int64_t arrived_real = static_cast<std::int64_t>(arv_buffer_get_system_timestamp(b));
    const std::int64_t waited = at->real_ns - arrived_real;
    if (arrived_real > 0 && waited >= 0 && waited < 1000000000) {
      at->real_ns = arrived_real;
      at->mono_ns -= waited;
    }
    impl_->last_frame_ns = at->mono_ns;
    CountFrameId(arv_buffer_get_frame_id(b));
    if (arv_buffer_get_status(b) != ARV_BUFFER_STATUS_SUCCESS) {
      ++stats_.incomplete;
      ++lost_pending_;
      arv_stream_push_buffer(impl_->stream, b);
      continue;
    }
    const ArvPixelFormat pf = arv_buffer_get_image_pixel_format(b);
    const int w = arv_buffer_get_image_width(b), h = arv_buffer_get_image_height(b);
    size_t size = 0;
    const auto* data = static_cast<const std::uint8_t*>(arv_buffer_get_image_data(b, &size));
    const Mono* fmt = FindMono(static_cast<std::uint32_t>(pf));
    const std::uint64_t pixels = static_cast<std::uint64_t>(std::max(w, 0)) * static_cast<std::uint64_t>(std::max(h, 0));
    if (!fmt || pixels == 0 || !video::FillsGroups(fmt->packing, pixels) ||
        size < video::PackedBytes(fmt->packing, pixels)) {
      arv_stream_push_buffer(impl_->stream, b);
      char s[16];
      std::snprintf(s, sizeof s, "%08x", static_cast<unsigned>(pf));
      *why = "Aravis camera '" + id_ + "': pixel format 0x" + s + (fmt ? " with " + std::to_string(w) + "x" +
                                                                              std::to_string(h) + " pixels does not fill its packing"
                                                                        : " is not Mono8, Mono10, Mono12, Mono16 or a "
                                                                          "packed Mono10/12 (set PixelFormat in the camera's features)");
      return GrabResult::kError;
    }
    if (fmt->packing == video::Packing::kU8) {
      out->create(h, w, CV_8UC1);
      video::Unpack8(data, pixels, out->ptr<std::uint8_t>());
    } else {
      // Deep samples scaled to 16 bits by bit replication, as lib/video delivers a camera file's.
      out->create(h, w, CV_16UC1);
      video::Unpack16(fmt->packing, fmt->bits, data, pixels, out->ptr<std::uint16_t>());
    }
    camera_ns_ = static_cast<std::int64_t>(arv_buffer_get_timestamp(b));
    lost_before_last_ = lost_pending_;
    lost_pending_ = 0;
    ++stats_.complete;
    arv_stream_push_buffer(impl_->stream, b);
    return GrabResult::kFrame;
  }
  return GrabResult::kStopped;
}

void AravisSource::EnablePtp() {
  ArvDevice* dev = arv_camera_get_device(impl_->camera);
  GError* e = nullptr;
  for (const auto& [on, status] : {std::pair<const char*, const char*>{"PtpEnable", "PtpStatus"},
                                   std::pair<const char*, const char*>{"GevIEEE1588", "GevIEEE1588Status"}}) {
    ArvGcNode* node = arv_device_get_feature(dev, on);
    if (!node || !ARV_IS_GC_FEATURE_NODE(node)) continue;
    arv_gc_feature_node_set_value_from_string(ARV_GC_FEATURE_NODE(node), "true", &e);
    const std::string set_error = TakeError(&e);
    const char* got = arv_gc_feature_node_get_value_as_string(ARV_GC_FEATURE_NODE(node), &e);
    g_clear_error(&e);
    ptp_ = {{"feature", on}, {"enabled", got ? std::string(got) : std::string()}};
    if (!set_error.empty()) ptp_["error"] = set_error;
    ArvGcNode* st = arv_device_get_feature(dev, status);
    if (st && ARV_IS_GC_FEATURE_NODE(st)) {
      const char* s = arv_gc_feature_node_get_value_as_string(ARV_GC_FEATURE_NODE(st), &e);
      g_clear_error(&e);
      if (s) ptp_["status"] = s;
    }
    return;
  }
  ptp_ = {{"error", "the camera has neither PtpEnable nor GevIEEE1588: no IEEE 1588"}};
}

void AravisSource::RaiseForReceiveThread() {
  policy_raised_ = nice_raised_ = false;
  sched_param sp{};
  pthread_getschedparam(pthread_self(), &saved_policy_, &sp);
  saved_priority_ = sp.sched_priority;
  sched_param rt{};
  rt.sched_priority = kReceiveFifoPriority;
  const int fifo_error = pthread_setschedparam(pthread_self(), SCHED_FIFO, &rt);
  if (fifo_error == 0) {
    policy_raised_ = true;
    receive_thread_ = "SCHED_FIFO priority " + std::to_string(kReceiveFifoPriority);
    return;
  }
  const std::string fifo_why = std::strerror(fifo_error);
  const id_t tid = static_cast<id_t>(gettid());
  errno = 0;
  saved_nice_ = getpriority(PRIO_PROCESS, tid);
  if (errno == 0 && setpriority(PRIO_PROCESS, tid, kReceiveNice) == 0) {
    nice_raised_ = true;
    receive_thread_ = "nice " + std::to_string(kReceiveNice) + " (SCHED_FIFO refused: " + fifo_why + ")";
    return;
  }
  receive_thread_ = "normal scheduling (SCHED_FIFO refused: " + fifo_why + "; nice " + std::to_string(kReceiveNice) +
                    " refused: " + std::strerror(errno) + ")";
}

void AravisSource::RestoreAfterReceiveThread() {
  if (policy_raised_) {
    sched_param sp{};
    sp.sched_priority = saved_priority_;
    pthread_setschedparam(pthread_self(), saved_policy_, &sp);
  }
  if (nice_raised_) setpriority(PRIO_PROCESS, static_cast<id_t>(gettid()), saved_nice_);
}

void AravisSource::CountFrameId(std::uint64_t id) {
  if (!gv_ || id == 0) return;  // 0: no id (USB3 Vision, or a buffer that never got one)
  if (!impl_->have_id) {
    impl_->last_id = id;
    impl_->have_id = true;
    return;
  }
  const std::uint64_t last = impl_->last_id;
  std::uint64_t forward = 0;
  bool ahead = false;
  if (id <= kFrameIdWrap && last <= kFrameIdWrap) {
    // 16-bit block ids 1..65535: the step forward modulo 65535; more than half the ring is a late buffer.
    forward = (id + kFrameIdWrap - last) % kFrameIdWrap;
    ahead = forward > 0 && forward <= kFrameIdWrap / 2;
  } else {
    forward = id > last ? id - last : 0;  // GigE Vision 2 extended (64-bit) ids
    ahead = forward > 0;
  }
  if (!ahead) return;  // the same frame again, or one that arrived after a later one
  stats_.never_arrived += forward - 1;
  lost_pending_ += static_cast<std::int64_t>(forward - 1);
  impl_->last_id = id;
}

AravisStreamStats AravisSource::stream_stats() const {
  AravisStreamStats s = stats_;
  if (impl_->stream) {
    guint64 completed = 0, failures = 0, underruns = 0;
    arv_stream_get_statistics(impl_->stream, &completed, &failures, &underruns);
    s.lost_buffers = underruns;
    if (gv_) {
      guint64 resent = 0, missing = 0;
      arv_gv_stream_get_statistics(ARV_GV_STREAM(impl_->stream), &resent, &missing);
      s.resent_packets = resent;
      s.missing_packets = missing;
    }
  }
  return s;
}

io::Json AravisSource::StreamReport() const {
  const AravisStreamStats s = stream_stats();
  io::Json features = io::Json::array();
  for (const FeatureResult& f : features_) {
    io::Json j = {{"name", f.name}, {"asked", f.asked}, {"got", f.got}};
    if (!f.error.empty()) j["error"] = f.error;
    features.push_back(j);
  }
  return {{"id", id_},
          {"gige", gv_},
          {"packet_size", packet_size_},
          {"opens", opens_},
          {"frames_complete", s.complete},
          {"frames_incomplete", s.incomplete},
          {"frames_never_arrived", s.never_arrived},
          {"resent_packets", s.resent_packets},
          {"missing_packets", s.missing_packets},
          {"lost_buffers", s.lost_buffers},
          {"timeouts", s.timeouts},
          {"ptp", ptp_},
          {"trigger", trigger_.report},
          {"receive_thread", receive_thread_},
          {"features", features}};
}

std::vector<AravisCameraInfo> ListAravisCameras() {
  arv_update_device_list();
  std::vector<AravisCameraInfo> out;
  const unsigned n = arv_get_n_devices();
  for (unsigned i = 0; i < n; ++i) {
    auto s = [](const char* c) { return std::string(c ? c : ""); };
    out.push_back({s(arv_get_device_id(i)), s(arv_get_device_model(i)), s(arv_get_device_serial_nbr(i)),
                   s(arv_get_device_address(i))});
  }
  return out;
}

}  // namespace rk::capture
