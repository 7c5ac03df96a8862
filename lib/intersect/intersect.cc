// rk-intersect's run: options, output times, the per-row loop; see intersect.h.
#include "intersect/intersect.h"

#include <algorithm>
#include <bit>
#include <cmath>
#include <limits>

#include "intersect/intersect_common.h"
#include "intersect/station_frames.h"
#include "geo/angles.h"
#include "io/error.h"

namespace rk::intersect {

const io::OptionTable<IntersectOptions>& IntersectOptions::Table() {
  static const io::OptionTable<IntersectOptions> table =
      io::OptionTable<IntersectOptions>()
          .Real("--rate", &IntersectOptions::rate_hz, "Hz", io::Bounds::AtLeast(0.0).Finite(),
                "Output times on the grid k/HZ (Hz) over the stations' span (0 = the union of the stations' row "
                "times; exclusive with --at)")
          .Real("--sigma-angle", &IntersectOptions::sigma_angle_arcsec, "arcsec", io::Bounds::Positive().Finite(),
                "1 sigma (arcsec) of azimuth across the line (az x cos el) and of elevation, for files "
                "without sigma_az_deg/sigma_el_deg columns")
          .Real("--sigma-range", &IntersectOptions::sigma_range_m, "m", io::Bounds::Positive().Finite(),
                "1 sigma (m) of a range, for files without a sigma_range_m column")
          .Real("--reject-sigma", &IntersectOptions::reject_sigma, "sigma", io::Bounds::Positive(),
                "A station whose standardised residual exceeds this is dropped for the row (needs >= 3 lines "
                "of sight; inf = never)")
          .Real("--max-gap-frames", &IntersectOptions::max_gap_frames, "frame intervals",
                io::Bounds::Closed(1.0, 10.0),
                "A station contributes at t only if its rows around t are at most this many of its median "
                "frame intervals apart")
          .Flag("--estimate-time-offsets", &IntersectOptions::estimate_time_offsets,
                "Estimate every station's clock offset against the reference station's (stations.json "
                "time_reference, else the first) jointly with the trajectory, with its 1 sigma; report "
                "time_offsets; the trajectory is intersected with them and its sigma includes theirs")
          .Flag("--smooth", &IntersectOptions::smooth,
                "Add velocity and acceleration columns (Singer RTS smoother of rk-smooth singer)")
          .Real("--smooth-gate", &IntersectOptions::smooth_gate, "x median sigma", io::Bounds::Positive().Finite(),
                "--smooth: rows whose 3-D sigma exceeds this times the median are not fed to the smoother")
          .Sub(&IntersectOptions::singer, filter::SingerSeriesOptions::Table());
  return table;
}

bool IntersectOptions::Check(std::string* why) const {
  if (!Table().Check(*this, why)) return false;
  return singer.Check(why);
}

TrackDefaults IntersectOptions::Defaults() const {
  TrackDefaults d;
  d.sigma_angle_rad = sigma_angle_arcsec / geo::kArcsecPerRad;
  d.sigma_range_m = sigma_range_m;
  d.max_gap_frames = max_gap_frames;
  return d;
}

std::vector<double> ReadTimes(const io::CsvTable& table) {
  const int c = table.RequireColumn("t_s");
  table.RequireIncreasing(c);
  std::vector<double> t;
  for (std::size_t i = 0; i < table.rows(); ++i) t.push_back(table.Double(i, c));
  if (t.empty()) throw DataError(table.name(), table.header_line(), 1, "no times");
  return t;
}

std::vector<double> OutputTimes(const std::vector<StationTrack>& tracks, const IntersectOptions& options,
                                const std::vector<double>& at) {
  if (!at.empty()) return at;
  std::vector<double> t;
  for (const StationTrack& s : tracks) t.insert(t.end(), s.row_times().begin(), s.row_times().end());
  std::sort(t.begin(), t.end());
  t.erase(std::unique(t.begin(), t.end()), t.end());
  if (options.rate_hz <= 0.0 || t.empty()) return t;
  std::vector<double> grid;
  const auto k0 = static_cast<long long>(std::ceil(t.front() * options.rate_hz - 1e-9));
  const auto k1 = static_cast<long long>(std::floor(t.back() * options.rate_hz + 1e-9));
  for (long long k = k0; k <= k1; ++k) grid.push_back(static_cast<double>(k) / options.rate_hz);
  return grid;
}

namespace {

void Record(const std::vector<StationFrame>& frames, const LineObservation* obs, int n, std::size_t row,
            IntersectResult* r) {
  const std::size_t S = r->names.size();
  TrajectoryRow& tr = r->rows[row];
  const Solution& sol = tr.result.solution;
  for (int i = 0; i < n; ++i) {
    const std::size_t s = static_cast<std::size_t>(obs[i].station);
    StationCounts& c = r->stations[s];
    ++c.rows_contributed;
    const bool used = (tr.result.used >> i) & 1U, rejected = (tr.result.rejected >> i) & 1U;
    if (sol.status != SolveStatus::kOk) continue;
    r->use[row * S + s] = used ? LineUse::kUsed : (rejected ? LineUse::kRejected : LineUse::kNone);
    const Prediction pr = Predict(frames[obs[i].station], sol.p);
    Eigen::Vector3d& res = r->residual[row * S + s];
    res(0) = geo::WrapPi(obs[i].az_rad - pr.az) * std::cos(obs[i].el_rad) * geo::kArcsecPerRad;
    res(1) = (obs[i].el_rad - pr.el) * geo::kArcsecPerRad;
    res(2) = obs[i].has_range ? obs[i].range_m - pr.range : std::numeric_limits<double>::quiet_NaN();
    if (used) {
      ++c.rows_used;
      c.sum2_az += res(0) * res(0), c.sum2_el += res(1) * res(1);
      if (obs[i].has_range) c.sum2_range += res(2) * res(2), ++c.n_range;
    }
    if (rejected) ++c.rows_rejected;
  }
}

void Classify(const geo::LocalEnu& origin, TrajectoryRow* tr, IntersectResult* r) {
  const Solution& sol = tr->result.solution;
  if (sol.status == SolveStatus::kTooFew) {
    tr->status = RowStatus::kLost;
    ++r->rows_lost;
  } else if (sol.status != SolveStatus::kOk) {
    tr->status = RowStatus::kInvalid;
    ++r->rows_invalid;
  } else {
    tr->status = RowStatus::kOk;
    tr->wgs84 = origin.ToGeodetic(sol.p);
    ++r->rows_ok;
    if (tr->result.rejected) ++r->rows_with_rejection;
  }
}

// The error when no output time has two lines of sight, saying which of three things is true: the stations'
// rows never overlap; they do, but every output time (--at, --rate) lies outside the overlaps (or outside every
// station's rows); or output times lie in an overlap but gaps or unusable rows leave fewer than two lines there.
[[noreturn]] void ThrowNoOverlap(const formats::StationsFile& stations, const std::vector<StationTrack>& tracks,
                                 const std::vector<double>& times) {
  std::string spans;
  const auto span_text = [](double a, double b) {
    char buf[64];
    std::snprintf(buf, sizeof buf, "[%.3f, %.3f] s", a, b);
    return std::string(buf);
  };
  std::vector<std::pair<double, double>> span;
  for (std::size_t s = 0; s < tracks.size(); ++s) {
    const auto& t = tracks[s].row_times();
    span.emplace_back(t.empty() ? NAN : t.front(), t.empty() ? NAN : t.back());
    spans += (s ? ", " : "") + stations.stations[s].name + " " + span_text(span.back().first, span.back().second);
  }
  std::size_t in_any = 0, in_overlap = 0;
  bool overlap = false;
  for (std::size_t a = 0; a < span.size(); ++a) {
    for (std::size_t b = a + 1; b < span.size(); ++b) {
      overlap = overlap || std::max(span[a].first, span[b].first) <= std::min(span[a].second, span[b].second);
    }
  }
  for (double t : times) {
    int n = 0;
    for (const auto& [lo, hi] : span) n += (t >= lo && t <= hi) ? 1 : 0;
    in_any += n > 0 ? 1 : 0;
    in_overlap += n > 1 ? 1 : 0;
  }
  std::string why;
  if (!overlap) {
    why = "the stations' usable times never overlap: " + spans;
  } else if (times.empty()) {
    why = "there are no output times (stations " + spans + ")";
  } else if (in_any == 0) {
    why = "all " + std::to_string(times.size()) + " output times, " + span_text(times.front(), times.back()) +
          ", lie outside every station's rows: " + spans;
  } else if (in_overlap == 0) {
    why = "none of the " + std::to_string(times.size()) + " output times, " + span_text(times.front(), times.back()) +
          ", lies where two stations' rows overlap: " + spans;
  } else {
    why = std::to_string(in_overlap) + " output times lie where two stations' rows overlap, but there fewer than "
          "two stations have usable rows within --max-gap-frames of them (gaps, empty angles or bad status): " + spans;
  }
  throw DataError(stations.path, 0, 0, "no output time has lines of sight from two stations (" + why + ")");
}

void Smooth(const IntersectOptions& options, IntersectResult* r);

}  // namespace

IntersectResult Intersect(const formats::StationsFile& stations, const std::vector<StationTrack>& tracks,
                          const std::vector<double>& times, const IntersectOptions& options) {
  RK_CHECK(stations.stations.size() == tracks.size(), "one track per station");
  IntersectResult r;
  std::vector<StationFrame> frames;
  for (std::size_t s = 0; s < tracks.size(); ++s) {
    frames.push_back(MakeStationFrame(stations.origin, stations.stations[s].position));
    r.names.push_back(stations.stations[s].name);
    r.has_range.push_back(tracks[s].has_range());
    r.station_enu.push_back(frames.back().a);
  }
  const std::size_t S = tracks.size();
  const geo::LocalEnu origin(stations.origin);
  r.rows.resize(times.size());
  r.use.assign(times.size() * S, LineUse::kNone);
  r.residual.assign(times.size() * S, Eigen::Vector3d::Constant(std::numeric_limits<double>::quiet_NaN()));
  r.stations.resize(S);
  std::vector<LineObservation> obs(S);
  const SolverOptions solver = options.Solver();
  for (std::size_t row = 0; row < times.size(); ++row) {
    TrajectoryRow& tr = r.rows[row];
    tr.t_s = times[row];
    int n = 0;
    for (std::size_t s = 0; s < S; ++s) {
      if (tracks[s].At(tr.t_s, &obs[n])) obs[n++].station = static_cast<int>(s);
    }
    tr.n_lines = n;
    if (Solvable(obs.data(), n, n >= 64 ? ~std::uint64_t{0} : (std::uint64_t{1} << n) - 1)) {
      tr.result = SolveRow(frames, obs.data(), n, solver);
    }
    Record(frames, obs.data(), n, row, &r);
    Classify(origin, &tr, &r);
  }
  if (r.rows_ok + r.rows_invalid == 0) ThrowNoOverlap(stations, tracks, times);
  if (options.smooth) Smooth(options, &r);
  return r;
}

namespace {

// Singer RTS smoother (lib/filter) on e, n, u of the gated rows; velocity and acceleration per ok row.
void Smooth(const IntersectOptions& options, IntersectResult* r) {
  filter::Series series;
  series.source = "trajectory";
  series.columns = {"e_m", "n_m", "u_m"};
  series.is_angle = {false, false, false};
  series.t_s.reserve(r->rows.size());
  series.values.setConstant(static_cast<Eigen::Index>(r->rows.size()), 3, std::numeric_limits<double>::quiet_NaN());
  std::vector<double> sigma3d;
  for (const TrajectoryRow& tr : r->rows) {
    if (tr.status == RowStatus::kOk) sigma3d.push_back(std::sqrt(tr.result.solution.P.trace()));
  }
  const double gate = options.smooth_gate * internal::UpperMedianOrNaN(sigma3d);
  std::vector<double> sig[3];
  for (std::size_t i = 0; i < r->rows.size(); ++i) {
    const TrajectoryRow& tr = r->rows[i];
    series.t_s.push_back(tr.t_s);
    if (tr.status != RowStatus::kOk || !(std::sqrt(tr.result.solution.P.trace()) <= gate)) continue;
    for (int c = 0; c < 3; ++c) {
      series.values(static_cast<Eigen::Index>(i), c) = tr.result.solution.p(c);
      sig[c].push_back(std::sqrt(tr.result.solution.P(c, c)));
    }
  }
  if (sig[0].size() < 3) return;
  filter::SingerSeriesOptions so = options.singer;
  if (so.meas_sigma.empty()) {
    so.meas_sigma = {internal::UpperMedianOrNaN(sig[0]), internal::UpperMedianOrNaN(sig[1]),
                     internal::UpperMedianOrNaN(sig[2])};
  }
  r->singer = filter::RunSingerSeries(series, so);
  r->smoothed = true;
  for (std::size_t i = 0; i < r->rows.size(); ++i) {
    TrajectoryRow& tr = r->rows[i];
    if (tr.status != RowStatus::kOk) continue;
    tr.has_kinematics = true;
    for (int c = 0; c < 3; ++c) {
      Eigen::Vector3d x;
      Eigen::Matrix3d P;
      if (!r->singer.At(static_cast<std::size_t>(c), i, &x, &P)) {
        tr.has_kinematics = false;
        break;
      }
      tr.v(c) = x(1), tr.a(c) = x(2);
      tr.sigma_v(c) = std::sqrt(P(1, 1)), tr.sigma_a(c) = std::sqrt(P(2, 2));
    }
  }
}

}  // namespace

}  // namespace rk::intersect
