#include "asterix/feed.h"

#include <sys/mman.h>

#include <algorithm>
#include <array>
#include <cmath>
#include <cstdio>
#include <filesystem>
#include <limits>
#include <map>
#include <memory>
#include <new>
#include <string_view>

#include "asterix/block.h"
#include "asterix/capture.h"
#include "geo/wgs84.h"
#include "io/error.h"
#include "io/number_text.h"
#include "numeric/robust_stats.h"

namespace rk::asterix {
namespace {

constexpr double kDay = 86400.0;
constexpr double kDuplicateWindowS = 10.0;  // a redundant feed's copy arrives milliseconds after the first
constexpr std::size_t kSaid = 20;  // bad records said one by one, then a count
constexpr std::size_t kLatencySamples = 100000;

// The instant (s since 1970) whose UTC time of day is `tod` nearest to `reference`.
double Nearest(double tod, double reference) {
  const double base = std::floor(reference / kDay) * kDay;
  double t = base + tod;
  if (t - reference > kDay / 2) t -= kDay;
  if (reference - t > kDay / 2) t += kDay;
  return t;
}

// The instant nearest to `reference` whose UTC time of day modulo 512 s is `truncated` (CAT001's I001/141). A day
// is not a whole number of 512-s periods (86400 = 168.75 × 512): the candidates are sought day by day.
double NearestTruncated(double truncated, double reference) {
  const double day = std::floor(reference / kDay) * kDay;
  double best = std::numeric_limits<double>::quiet_NaN();
  for (int d = -1; d <= 1; ++d) {
    const double start = day + d * kDay;
    const double k0 = std::round((reference - start - truncated) / 512.0);
    for (double k = k0 - 1; k <= k0 + 1; ++k) {
      const double tod = truncated + 512.0 * k;
      if (tod < 0 || tod >= kDay) continue;
      if (!(std::abs(start + tod - reference) >= std::abs(best - reference))) best = start + tod;
    }
  }
  return best;
}

// Hashes of the records seen lately, for a redundant feed's copies: two generations of an open-addressing set,
// the older dropped every half window, so a record is remembered for between 5 and 10 s (copies arrive
// milliseconds apart; the tables stay small enough for the cache). No allocation per record, no node chasing (an unordered_map spent most of the decoding
// time in its buckets).
class RecentRecords {
 public:
  // True when `key` (never 0) was seen in either generation; else remembers it.
  bool SeenOrAdd(std::uint64_t key, double now_s) {
    // A new generation each half window forward in time. Backwards, only a jump of an hour or more (the next
    // input starting earlier): a stale report (a real feed has some 20 s old among the others) must not
    // drop the generation its copy is in.
    const double since = now_s - generation_start_s_;
    if (!(since < kDuplicateWindowS / 2 && since > -3600.0)) {
      std::swap(current_, previous_);
      current_.Clear();
      generation_start_s_ = now_s;
    }
    if (previous_.Contains(key)) return true;
    return !current_.Insert(key);
  }

 private:
  class Set {
   public:
    bool Contains(std::uint64_t key) const {
      if (slots_.empty()) return false;
      for (std::size_t i = key & mask_;; i = (i + 1) & mask_) {
        if (slots_[i] == key) return true;
        if (slots_[i] == 0) return false;
      }
    }
    // False when it was there already.
    bool Insert(std::uint64_t key) {
      if (2 * (size_ + 1) > slots_.size()) Grow();
      for (std::size_t i = key & mask_;; i = (i + 1) & mask_) {
        if (slots_[i] == key) return false;
        if (slots_[i] == 0) {
          slots_[i] = key;
          ++size_;
          return true;
        }
      }
    }
    void Clear() {
      std::fill(slots_.begin(), slots_.end(), 0);
      size_ = 0;
    }

   private:
    void Grow() {
      std::vector<std::uint64_t> old = std::move(slots_);
      slots_.assign(std::max<std::size_t>(1 << 12, 2 * old.size()), 0);
      mask_ = slots_.size() - 1;
      size_ = 0;
      for (std::uint64_t k : old) {
        if (k != 0) Insert(k);
      }
    }
    std::vector<std::uint64_t> slots_;
    std::size_t mask_ = 0, size_ = 0;
  };
  Set current_, previous_;
  double generation_start_s_ = -std::numeric_limits<double>::infinity();
};

struct RadarState {
  std::string name;
  int sac = 0, sic = 0;
  const formats::RadarSite* site = nullptr;
  std::unique_ptr<geo::LocalEnu> enu;  // when the site has a position
  std::size_t plots = 0, with_el_3d = 0, with_el_mode_c = 0, height_unreachable = 0, heights_without_position = 0;
  std::size_t simulated = 0, test_targets = 0, mode3a_invalid = 0, flight_level_invalid = 0;
  std::vector<double> north_markers_t_s;
  std::size_t sector_crossings = 0;
  double rotation_period_s = std::numeric_limits<double>::quiet_NaN();
  double first_t_s = std::numeric_limits<double>::quiet_NaN(), last_t_s = first_t_s;
};

struct SourceKey {
  std::uint32_t src_ip = 0, dst_ip = 0;
  std::uint16_t src_port = 0, dst_port = 0;
  std::size_t raw_input = 0;  // 1 + index of a raw stream's input, else 0
  bool operator==(const SourceKey&) const = default;
};

struct SourceState {
  SourceKey key;
  std::string name;  // "10.17.58.184:21124 -> 232.2.1.31:22131", or the file of a raw stream
  std::size_t datagrams = 0, records = 0, duplicates = 0;
};

class Importer : public BlockVisitor {
 public:
  explicit Importer(const FeedOptions& o) : options_(o) {
    radar_of_.fill(-1);
    for (const formats::RadarSite& s : options_.radars) Radar(static_cast<std::uint8_t>(s.sac), static_cast<std::uint8_t>(s.sic));
  }

  void Read(const std::string& path) {
    file_ = &path;
    // Room for every plot the file can hold (a target report takes at least 12 octets of it): reserved address
    // space only, touched as rows come, so the rows are never copied to a larger vector (that copy, and the
    // page faults of each new copy, were a fifth of the time on a 2-million-report feed).
    std::error_code ec;
    const std::uintmax_t bytes = std::filesystem::file_size(path, ec);
    if (!ec) {
      // At most 16 M rows ahead (0.9 GB of address space); a system that refuses even that (strict overcommit)
      // just grows the vector as it goes.
      try {
        result_.rows.reserve(std::min<std::size_t>(result_.rows.size() + bytes / 12, result_.rows.size() + (1u << 24)));
      } catch (const std::bad_alloc&) {
      }
      // Huge pages where the kernel offers them on request (transparent_hugepage=madvise, Debian's default): one
      // page fault per 2 MiB of rows instead of per 4 KiB.
      const auto begin = reinterpret_cast<std::uintptr_t>(result_.rows.data() + result_.rows.size());
      const auto end = reinterpret_cast<std::uintptr_t>(result_.rows.data() + result_.rows.capacity());
      constexpr std::uintptr_t kHuge = std::uintptr_t{2} << 20;
      const std::uintptr_t first = (begin + kHuge - 1) & ~(kHuge - 1);
      if (end > first + kHuge) madvise(reinterpret_cast<void*>(first), (end - first) & ~(kHuge - 1), MADV_HUGEPAGE);
    }
    reference_unix_s_ = options_.epoch_unix_s;
    CaptureStats stats;
    const auto on_datagram = [&](const Datagram& d) { OnDatagram(d); };
    const CaptureProblem on_problem = [&](std::uint64_t offset, const std::string& reason) {
      Bad(offset, reason);
    };
    ReadCapture(path, on_datagram, on_problem, &stats);
    io::Json in = {{"file", path},
                   {"format", stats.format},
                   {"packets", stats.packets},
                   {"udp_datagrams", stats.udp_datagrams},
                   {"other_packets", stats.other_packets},
                   {"ip_fragments", stats.fragments},
                   {"reassembled_datagrams", stats.reassembled},
                   {"incomplete_datagrams", stats.incomplete_datagrams},
                   {"truncated_packets", stats.truncated_packets}};
    if (!stats.link_type.empty()) in["link_type"] = stats.link_type;
    inputs_.push_back(std::move(in));
    if (stats.incomplete_datagrams > 0) {
      result_.summary.Warn("incomplete_datagrams",
                           path + ": " + std::to_string(stats.incomplete_datagrams) +
                               " IP datagrams never completed from their fragments (fragments lost, or cut by the "
                               "capture's start or end): their records are missing");
    }
  }

  FeedResult Finish() {
    // Time order (stable: records of one instant keep their arrival order).
    std::size_t out_of_order = 0;
    for (std::size_t i = 1; i < result_.rows.size(); ++i) out_of_order += result_.rows[i].t_s < result_.rows[i - 1].t_s;
    if (out_of_order > 0) std::stable_sort(result_.rows.begin(), result_.rows.end(),
                     [](const formats::AsterixPlotRow& a, const formats::AsterixPlotRow& b) { return a.t_s < b.t_s; });
    io::RunSummary& s = result_.summary;
    if (bad_ > kSaid) {
      s.Warn("bad_records", std::to_string(bad_ - kSaid) + " more bad records skipped (" + std::to_string(bad_) +
                                " in all)");
    }
    io::Json radars = io::Json::array();
    std::size_t heights_without_position = 0;
    for (RadarState& r : radars_) {
      result_.radar_names.push_back(r.name);
      io::Json j = {{"name", r.name}, {"sac", r.sac}, {"sic", r.sic}, {"plots", r.plots},
                    {"el_3d", r.with_el_3d}, {"el_mode_c", r.with_el_mode_c},
                    {"simulated", r.simulated}, {"test_targets", r.test_targets},
                    {"mode3a_not_validated_or_garbled", r.mode3a_invalid},
                    {"flight_level_not_validated_or_garbled", r.flight_level_invalid},
                    {"north_markers", r.north_markers_t_s.size()}, {"sector_crossings", r.sector_crossings}};
      j["position_known"] = r.enu != nullptr;
      j["first_t_s"] = r.first_t_s;
      j["last_t_s"] = r.last_t_s;
      j["north_marker_t_s"] = r.north_markers_t_s;
      std::vector<double> scans;
      for (std::size_t i = 1; i < r.north_markers_t_s.size(); ++i) {
        scans.push_back(r.north_markers_t_s[i] - r.north_markers_t_s[i - 1]);
      }
      // From the north markers (null: fewer than two).
      j["scan_period_s"] = scans.empty() ? std::numeric_limits<double>::quiet_NaN() : numeric::UpperMedian(scans);
      j["antenna_rotation_period_s"] = r.rotation_period_s;  // I034/041, as the radar states it
      radars.push_back(std::move(j));
      if (r.height_unreachable > 0) {
        s.Warn("height_unreachable", "radar " + r.name + ": " + std::to_string(r.height_unreachable) +
                                         " plots whose height cannot be reached at their range: el_deg empty");
      }
      if (r.heights_without_position > 0 && !options_.radars.empty()) {
        s.Warn("no_radar_position", "radar " + r.name + ": " + std::to_string(r.heights_without_position) +
                                        " plots carry a height or flight level but radars.json gives no position for "
                                        "it: el_deg empty");
      }
      heights_without_position += r.heights_without_position;
    }
    if (heights_without_position > 0 && options_.radars.empty()) {
      s.Warn("no_radar_position", std::to_string(heights_without_position) +
                                      " plots carry a height or flight level, but without --radars no radar's position "
                                      "is known: el_deg empty (el_source too)");
    }
    for (const RadarState& r : radars_) {
      if (r.site == nullptr && !options_.radars.empty()) {
        s.Warn("radar_not_listed", "SAC " + std::to_string(r.sac) + " SIC " + std::to_string(r.sic) +
                                       " is not in --radars: named " + r.name);
      }
    }
    io::Json sources = io::Json::array();
    for (const SourceState& src : sources_) {
      sources.push_back({{"source", src.name}, {"datagrams", src.datagrams}, {"records", src.records},
                         {"duplicates", src.duplicates}});
    }
    const double latency =
        latency_s_.empty() ? std::numeric_limits<double>::quiet_NaN() : numeric::UpperMedian(latency_s_);
    if (std::isfinite(latency) && std::abs(latency) > 60.0) {
      s.Warn("capture_clock", "packets were captured a median " + io::NumberText(latency) +
                                  " s after their records' time of day: check the capture host's clock (the date "
                                  "of each record comes from it)");
    }
    std::size_t written = result_.rows.size();
    s.AddFigure("plots", static_cast<double>(written), "", std::to_string(radars_.size()) + " radars");
    s.AddFigure("duplicates dropped", static_cast<double>(duplicates_), "");
    s.AddFigure("bad records", static_cast<double>(bad_), "");
    s.details["asterix"] = {{"inputs", inputs_},
                            {"sources", sources},
                            {"radars", radars},
                            {"records", {{"cat048", by_cat_[48]}, {"cat034", by_cat_[34]}, {"cat001", by_cat_[1]}}},
                            {"duplicates", duplicates_},
                            {"bad_records", bad_},
                            {"reports_without_position", no_position_},
                            {"reports_without_time", no_time_},
                            {"cat001_timed_by_capture", timed_by_capture_},
                            {"rows_out_of_arrival_order", out_of_order},
                            {"capture_minus_record_s", latency}};
    return std::move(result_);
  }

  void OnRecord(const RecordLayout& record, std::size_t offset) override {
    ++by_cat_[record.category->category];
    SourceState& src = sources_[source_];
    ++src.records;
    // A redundant feed: the same octets again within the window of the record's own time (so a copy is found
    // whatever the capture did: one capture of both groups, or several inputs read one after the other).
    const std::string_view bytes(reinterpret_cast<const char*>(record.data), record.size);
    // The key: a 64-bit hash of the octets and the category, never 0 (the empty slot). Two different records
    // collide with probability 2^-64 per pair.
    std::uint64_t key = std::hash<std::string_view>{}(bytes) ^ (std::uint64_t{record.category->category} << 56);
    key = key == 0 ? 1 : key;
    if (record.category->category == 34) {
      Service(DecodeServiceMessage(record), offset, key);
    } else {
      Report(DecodeTargetReport(record), offset, key);
    }
  }

  void OnBad(std::size_t offset, std::uint8_t category, const char* reason) override {
    std::string what = reason;
    if (category != 0) {
      char c[16];
      std::snprintf(c, sizeof c, " (CAT%03u)", category);
      what += c;
    }
    Bad(base_offset_ + offset, what + Where());
  }

 private:
  // " (packet 12)": where a capture's problem lies, for the message.
  std::string Where() const {
    if (packet_ == 0) return "";
    return std::string(" (packet ") + std::to_string(packet_) + (reassembled_ ? ", reassembled from IP fragments" : "") + ")";
  }

  void Bad(std::uint64_t offset, const std::string& reason) {
    if (options_.bad_records_error) throw ByteOffsetError(*file_, offset, reason);
    ++bad_;
    if (bad_ <= kSaid) {
      result_.summary.Warn("bad_record", ByteOffsetError(*file_, offset, reason + ": skipped").what());
    }
  }

  void OnDatagram(const Datagram& d) {
    capture_unix_s_ = d.capture_unix_s;
    if (std::isfinite(d.capture_unix_s)) reference_unix_s_ = d.capture_unix_s;
    base_offset_ = d.file_offset;
    packet_ = d.packet;
    reassembled_ = d.reassembled;
    // The source: sender and group of a datagram, or the raw stream's file (a few per feed: a linear search,
    // the last one first).
    const SourceKey key{d.src_ip, d.dst_ip, d.src_port, d.dst_port, d.packet == 0 ? inputs_.size() + 1 : 0};
    if (source_ >= sources_.size() || !(sources_[source_].key == key)) {
      source_ = 0;
      while (source_ < sources_.size() && !(sources_[source_].key == key)) ++source_;
      if (source_ == sources_.size()) {
        sources_.push_back({key, d.packet == 0 ? *file_
                                                : EndpointText(d.src_ip, d.src_port) + " -> " +
                                                      EndpointText(d.dst_ip, d.dst_port)});
      }
    }
    ++sources_[source_].datagrams;
    WalkBlocks(d.data, d.size, this);
  }

  RadarState& Radar(std::uint8_t sac, std::uint8_t sic) {
    int& index = radar_of_[std::size_t{sac} << 8 | sic];
    if (index < 0) {
      index = static_cast<int>(radars_.size());
      RadarState r;
      r.sac = sac;
      r.sic = sic;
      r.name = std::to_string(sac) + "-" + std::to_string(sic);
      for (const formats::RadarSite& s : options_.radars) {
        if (s.sac == sac && s.sic == sic) {
          r.site = &s;
          r.name = s.name;
          if (s.position) r.enu = std::make_unique<geo::LocalEnu>(*s.position);
        }
      }
      radars_.push_back(std::move(r));
    }
    return radars_[static_cast<std::size_t>(index)];
  }

  // Absolute time (s since 1970) of a full time of day; updates the raw stream's reference.
  double Absolute(double tod) {
    const double t = Nearest(tod, reference_unix_s_);
    if (std::isfinite(capture_unix_s_)) {
      if (latency_s_.size() < kLatencySamples) latency_s_.push_back(capture_unix_s_ - t);
    } else {
      reference_unix_s_ = t;
    }
    return t;
  }

  // True (and counted against the current source) when the record with `key` at `unix_s` was seen already.
  bool Duplicate(std::uint64_t key, double unix_s) {
    if (!recent_.SeenOrAdd(key, unix_s)) return false;
    ++sources_[source_].duplicates;
    ++duplicates_;
    return true;
  }

  void Report(const TargetReport& t, std::size_t offset, std::uint64_t key) {
    if (!t.has_source) {
      OnBad(offset, t.category, "target report without its data source identifier (SAC/SIC)");
      return;
    }
    double unix_s = 0.0;
    if (std::isfinite(t.time_of_day_s)) {
      unix_s = Absolute(t.time_of_day_s);
    } else if (std::isfinite(t.truncated_time_of_day_s)) {
      const double reference = reference_unix_s_;
      unix_s = NearestTruncated(t.truncated_time_of_day_s, reference);
      if (!std::isfinite(capture_unix_s_)) reference_unix_s_ = unix_s;
    } else if (std::isfinite(capture_unix_s_)) {
      unix_s = capture_unix_s_;
      ++timed_by_capture_;
      if (timed_by_capture_ == 1) {
        result_.summary.Warn("timed_by_capture", *file_ + ": target reports without a time of day are timed by "
                                                          "their packet's capture time (see the report's count)");
      }
    } else {
      ++no_time_;
      OnBad(offset, t.category, "target report without a time of day in a raw stream (no capture time either)");
      return;
    }
    if (Duplicate(key, unix_s)) return;
    if (!std::isfinite(t.rho_m)) {
      ++no_position_;  // a track-only record, or a report without a measured position: not a plot
      return;
    }
    RadarState& r = Radar(t.sac, t.sic);
    formats::AsterixPlotRow row;
    row.t_s = unix_s - options_.epoch_unix_s;
    row.radar = static_cast<std::uint16_t>(&r - radars_.data());
    row.range_m = t.rho_m;
    row.az_deg = t.theta_deg;
    row.el_deg = std::numeric_limits<double>::quiet_NaN();
    row.track_id = t.track_number;
    row.sac = t.sac;
    row.sic = t.sic;
    row.flight_level = static_cast<float>(t.flight_level);
    row.height_m = static_cast<float>(t.height_m);
    row.mode3a = static_cast<std::int16_t>(t.mode3a);
    row.address = t.address;
    const bool has_height = std::isfinite(t.height_m), has_fl = std::isfinite(t.flight_level);
    if (has_height || has_fl) {
      if (r.enu == nullptr) {
        ++r.heights_without_position;
      } else {
        const double h = has_height ? t.height_m : t.flight_level * 100.0 * kMetresPerFoot;
        const std::optional<double> el = geo::ElevationToHeight(*r.enu, t.rho_m, t.theta_deg * M_PI / 180.0, h);
        if (el) {
          row.el_deg = *el * 180.0 / M_PI;
          row.el_source = has_height ? formats::ElevationSource::k3d : formats::ElevationSource::kModeC;
          ++(has_height ? r.with_el_3d : r.with_el_mode_c);
        } else {
          ++r.height_unreachable;
        }
      }
    }
    ++r.plots;
    r.simulated += t.simulated;
    r.test_targets += t.test_target;
    r.mode3a_invalid += t.mode3a_invalid;
    r.flight_level_invalid += t.flight_level_invalid;
    if (!(r.first_t_s <= row.t_s)) r.first_t_s = row.t_s;
    if (!(r.last_t_s >= row.t_s)) r.last_t_s = row.t_s;
    result_.rows.push_back(row);
  }

  void Service(const ServiceMessage& m, std::size_t offset, std::uint64_t key) {
    if (!m.has_source || !std::isfinite(m.time_of_day_s)) {
      OnBad(offset, 34, "service message without its data source identifier or time of day");
      return;
    }
    const double unix_s = Absolute(m.time_of_day_s);
    if (Duplicate(key, unix_s)) return;
    RadarState& r = Radar(m.sac, m.sic);
    const double t_s = unix_s - options_.epoch_unix_s;
    if (m.message_type == 1) r.north_markers_t_s.push_back(t_s);
    if (m.message_type == 2) ++r.sector_crossings;
    if (std::isfinite(m.rotation_period_s)) r.rotation_period_s = m.rotation_period_s;
  }


  const FeedOptions& options_;
  FeedResult result_;
  std::array<int, 65536> radar_of_{};
  std::vector<RadarState> radars_;
  std::vector<SourceState> sources_;
  std::size_t source_ = std::numeric_limits<std::size_t>::max();
  RecentRecords recent_;
  const std::string* file_ = nullptr;
  double capture_unix_s_ = 0.0, reference_unix_s_ = 0.0;
  std::uint64_t base_offset_ = 0, packet_ = 0;
  bool reassembled_ = false;
  std::array<std::size_t, 256> by_cat_{};
  std::size_t bad_ = 0, duplicates_ = 0, no_position_ = 0, no_time_ = 0, timed_by_capture_ = 0;
  std::vector<double> latency_s_;
  io::Json inputs_ = io::Json::array();
};

}  // namespace

FeedResult ImportFeed(const std::vector<std::string>& inputs, const FeedOptions& options) {
  Importer importer(options);
  for (const std::string& path : inputs) importer.Read(path);
  return importer.Finish();
}

}  // namespace rk::asterix
