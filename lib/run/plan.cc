#include "run/plan.h"

#include <algorithm>
#include <cstdio>
#include <cstdlib>
#include <map>
#include <stdexcept>

#include "formats/stations.h"
#include "trial/layout.h"

namespace rk::run {
using io::Json;

const char* PlanStateName(PlanState s) {
  switch (s) {
    case PlanState::kActive: return "active";
    case PlanState::kOff: return "off";
    case PlanState::kNotApplicable: return "not-applicable";
  }
  return "?";
}

std::string Step::FileStem() const {
  std::string s = id;
  std::replace(s.begin(), s.end(), '/', '.');
  return s;
}

namespace {

std::string NumberText(const Json& v) {
  if (v.is_number_integer() || v.is_number_unsigned()) return v.dump();
  char buf[64];
  std::snprintf(buf, sizeof buf, "%.17g", v.get<double>());
  // Shortest form that reads back the same.
  for (int prec = 1; prec <= 17; ++prec) {
    char b[64];
    std::snprintf(b, sizeof b, "%.*g", prec, v.get<double>());
    if (std::strtod(b, nullptr) == v.get<double>()) return b;
  }
  return buf;
}

std::string ValueText(const Json& v) {
  if (v.is_string()) return v.get<std::string>();
  if (v.is_number()) return NumberText(v);
  return v.dump();
}

class PlanBuilder {
 public:
  PlanBuilder(const TrialManifest& m, const PlanOptions& o) : m_(m), o_(o) {}

  std::vector<Step> Build() {
    for (const trial::StationEntry& st : m_.stations) {
      st_ = &st;
      for (const auto& cam : st.cameras) {
        switch (cam.role) {
          case CameraRole::kBeacon: Beacon(cam); break;
          case CameraRole::kFeatures: Features(cam); break;
          case CameraRole::kSilhouette: Silhouette(cam); break;
          case CameraRole::kPoints: Points(cam); break;
        }
      }
    }
    st_ = nullptr;
    if (m_.radar) Radar(*m_.radar);
    if (m_.multi_station()) Intersect();
    Export();
    return steps_;
  }

 private:
  Step Make(const std::string& unit, const std::string& kind) {
    const StepKindInfo* info = FindStepKind(kind);
    Step s;
    s.id = unit + "/" + kind;
    s.unit = unit;
    s.kind = kind;
    s.tool = info->tool;
    s.subcommand = info->subcommand;
    if (!s.subcommand.empty()) s.args.push_back({s.subcommand});
    s.settings = m_.Settings(unit, kind);
    if (!s.settings.enabled) {
      s.state = PlanState::kOff;
      s.note = "switched off in trial.json \"steps\"";
    }
    return s;
  }
  // "--option value" (or "-o value") of an input binding. The option must be one of the kind's
  // bindings (StepKindInfo::bindings): those are the options a manifest may not override.
  static void Bind(Step* s, const std::string& option, const std::string& value, bool out_path = false) {
    std::string name = option;
    while (!name.empty() && name[0] == '-') name.erase(0, 1);
    const StepKindInfo* info = FindStepKind(s->kind);
    if (info == nullptr || std::find(info->bindings.begin(), info->bindings.end(), name) == info->bindings.end()) {
      throw std::logic_error("rk-run plan: step kind " + s->kind + " binds " + option +
                             ", which is not among its bindings in StepKinds()");
    }
    s->args.push_back({option[0] == '-' ? option : "--" + option});
    s->args.push_back({value, out_path});
  }
  static void In(Step* s, const std::string& option, const std::string& path) {
    Bind(s, option, path);
    s->inputs.push_back({option, path});
  }
  static void Out(Step* s, const std::string& option, const std::string& rel) {
    s->args.push_back({option});
    s->args.push_back({rel, true});
    s->outputs.push_back(rel);
  }
  // An input that is another step's product.
  void Upstream(Step* s, const std::string& option, const Step& from, const std::string& rel) {
    Bind(s, option, rel, true);
    Depend(s, from);
  }
  void Depend(Step* s, const Step& from) {
    s->depends_on.push_back(from.id);
    if (s->state == PlanState::kActive && from.state != PlanState::kActive) {
      s->state = PlanState::kNotApplicable;
      s->note = "needs " + from.id + ", which is " + PlanStateName(from.state);
    }
  }
  void NotApplicable(Step* s, const std::string& why) {
    if (s->state == PlanState::kActive) {
      s->state = PlanState::kNotApplicable;
      s->note = why;
    }
  }
  // The manifest's options go before the outputs rk-run names, so that rk-run's own output options come
  // last on the command line: a parser where the last of a repeated option wins still writes where
  // rk-run says (the options themselves are checked against the tool's --help before any step runs).
  void Finish(Step* s) {
    const std::vector<std::string> over = OverrideArgs(s->settings);
    if (!over.empty()) {
      std::vector<StepArg> args, outs;
      for (std::size_t i = 0; i < s->args.size(); ++i) {
        const bool output = i + 1 < s->args.size() && s->args[i + 1].out_path &&
                            std::find(s->outputs.begin(), s->outputs.end(), s->args[i + 1].text) != s->outputs.end();
        if (output) {
          outs.push_back(s->args[i]);
          outs.push_back(s->args[++i]);
        } else {
          args.push_back(s->args[i]);
        }
      }
      for (const auto& a : over) args.push_back({a});
      args.insert(args.end(), outs.begin(), outs.end());
      s->args = std::move(args);
    }
    steps_.push_back(*s);
  }
  void Video(Step* s, const CameraEntry& cam) {
    for (const auto& v : cam.video) In(s, "video", v);
    if (!cam.frames.empty()) {
      In(s, "frames", cam.frames);
    } else {
      Bind(s, "fps", NumberText(Json(*cam.fps)));
      if (cam.t0_s) Bind(s, "t0", NumberText(Json(*cam.t0_s)));
    }
  }
  void Plot(const Step& of, const std::string& series, const std::string& table, const std::string& columns,
            const std::string& title) {
    if (!o_.plots) return;
    Step s;
    s.id = of.unit + "/plot-" + series;
    s.unit = of.unit;
    s.kind = "plot";
    s.tool = "rk-plot";
    s.settings = m_.Settings(of.unit, "plot");
    s.warn_only = true;
    s.tool_report = false;
    if (!s.settings.enabled) {
      s.state = PlanState::kOff;
      s.note = "switched off in trial.json \"steps\"";
    }
    Upstream(&s, "-i", of, table);
    const bool user_columns = std::any_of(s.settings.options.begin(), s.settings.options.end(),
                                          [](const auto& o) { return o.first == "columns"; });
    if (!user_columns) {
      s.args.push_back({"--columns"});
      if (columns.empty()) {
        s.args.push_back({"@columns"});  // chosen from the table's header when the step starts
        s.plot_columns_from = table;
      } else {
        s.args.push_back({columns});
      }
    }
    const bool user_title = std::any_of(s.settings.options.begin(), s.settings.options.end(),
                                        [](const auto& o) { return o.first == "title"; });
    if (!user_title) {
      s.args.push_back({"--title"});
      s.args.push_back({m_.name + " " + of.unit + ": " + title});
    }
    std::string stem = of.unit;
    std::replace(stem.begin(), stem.end(), '/', '_');
    Out(&s, "-o", "plots/" + stem + "_" + series + ".png");
    Finish(&s);
  }

  // The station's pointing model (SPEC.md §3.1 "station": {..., "pointing"}) as --pointing, and with
  // `position` its WGS-84 position as --station LAT,LON,H.
  void Station(Step* s, bool position) {
    if (!st_->pointing.empty()) In(s, "pointing", st_->pointing);
    if (position && st_->station.is_object()) Bind(s, "station", Geodetic(st_->station));
  }
  static std::string Geodetic(const Json& p) {
    return NumberText(p.at("lat_deg")) + "," + NumberText(p.at("lon_deg")) + "," + NumberText(p.at("h_m"));
  }

  // rk-locate of a track (a beacon's, or a points track: one series per id) from step `ex`, with the turret
  // (else theodolite) log, the range log and the station; into <unit>/located.csv, which the intersection takes.
  Step Locate(const std::string& unit, const char* kind, const CameraEntry& cam, const Step& ex,
              const std::string& track) {
    const std::string angles = !st_->turret.empty() ? st_->turret : st_->theodolite;
    const std::string located = unit + "/located.csv";
    Step lo = Make(unit, kind);
    Upstream(&lo, "--track", ex, track);
    In(&lo, "camera", cam.model);
    if (angles.empty()) {
      NotApplicable(&lo, "the manifest has no turret or theodolite log");
    } else {
      In(&lo, "turret", angles);
    }
    if (!st_->range.empty()) In(&lo, "range", st_->range);
    Station(&lo, true);
    Out(&lo, "-o", located);
    lo.table = located;
    Finish(&lo);
    if (lo.state == PlanState::kActive) located_.push_back({unit, located, lo.id});
    return lo;
  }

  void Beacon(const CameraEntry& cam) {
    const std::string unit = st_->Unit(cam), dir = unit + "/";
    Step ex = Make(unit, "extract-beacon");
    Video(&ex, cam);
    Out(&ex, "-o", dir + "track.csv");
    ex.table = dir + "track.csv";
    Finish(&ex);

    const Step lo = Locate(unit, "locate", cam, ex, dir + "track.csv");
    Plot(lo, "located", dir + "located.csv", st_->range.empty() ? "az_deg,el_deg" : "az_deg,el_deg,range_m",
         "located target");

    Step sm = Make(unit, "smooth");
    Upstream(&sm, "-i", lo, dir + "located.csv");
    const bool user_columns = std::any_of(sm.settings.options.begin(), sm.settings.options.end(),
                                          [](const auto& o) { return o.first == "columns"; });
    if (!user_columns) {
      sm.args.push_back({"--columns"});
      sm.args.push_back({st_->range.empty() ? "az_deg,el_deg" : "az_deg,el_deg,range_m,e_m,n_m,u_m"});
    }
    Out(&sm, "-o", dir + "smoothed.csv");
    sm.table = dir + "smoothed.csv";
    Finish(&sm);
    Plot(sm, "rates", dir + "smoothed.csv",
         st_->range.empty() ? "az_rate_deg_s,el_rate_deg_s" : "e_rate_m_s,n_rate_m_s,u_rate_m_s",
         "smoothed rates");

    Step rs = Make(unit, "resample-range");
    if (st_->range.empty()) {
      NotApplicable(&rs, "the manifest has no range log");
    } else if (cam.frames.empty()) {
      NotApplicable(&rs, "the camera has no frame-times CSV");
    } else {
      Bind(&rs, "-i", st_->range);
      rs.inputs.push_back({"input", st_->range});
      const bool user_columns_rs = std::any_of(rs.settings.options.begin(), rs.settings.options.end(),
                                               [](const auto& o) { return o.first == "columns"; });
      if (!user_columns_rs) {
        rs.args.push_back({"--columns"});
        rs.args.push_back({"range_m"});
      }
      In(&rs, "at", cam.frames);
    }
    Out(&rs, "-o", dir + "range_at_frames.csv");
    rs.table = dir + "range_at_frames.csv";
    Finish(&rs);
  }

  void Features(const CameraEntry& cam) {
    const std::string unit = st_->Unit(cam), dir = unit + "/";
    Step ex = Make(unit, "extract-features");
    Video(&ex, cam);
    In(&ex, "target", cam.target);
    Out(&ex, "-o", dir + "points.csv");
    ex.table = dir + "points.csv";
    Finish(&ex);

    Step at = Make(unit, "attitude-oi");
    Upstream(&at, "--points", ex, dir + "points.csv");
    In(&at, "camera", cam.model);
    In(&at, "target", cam.target);
    if (!st_->turret.empty()) {
      In(&at, "turret", st_->turret);
    } else if (cam.boresight_deg) {
      Bind(&at, "boresight",
           NumberText(Json(cam.boresight_deg->first)) + "," + NumberText(Json(cam.boresight_deg->second)));
    } else {
      NotApplicable(&at, "the manifest has no turret log and the camera no boresight_deg");
    }
    Station(&at, false);
    Out(&at, "-o", dir + "pose.csv");
    at.table = dir + "pose.csv";
    Finish(&at);
    Plot(at, "pose", dir + "pose.csv", "yaw_deg,pitch_deg,roll_deg", "attitude (oi)");
  }

  // User-seeded points (rk-extract points) and their lines of sight per id (rk-locate of the points track),
  // which the intersection of a multi-station trial takes like a beacon's (one trajectory per id).
  void Points(const CameraEntry& cam) {
    const std::string unit = st_->Unit(cam), dir = unit + "/";
    Step ex = Make(unit, "extract-points");
    Video(&ex, cam);
    In(&ex, "seeds", cam.seeds);
    Out(&ex, "-o", dir + "points.csv");
    ex.table = dir + "points.csv";
    Finish(&ex);

    const Step lo = Locate(unit, "locate-points", cam, ex, dir + "points.csv");
    Plot(lo, "located", dir + "located.csv", "az_deg,el_deg", "located points");
  }

  void Silhouette(const CameraEntry& cam) {
    const std::string unit = st_->Unit(cam), dir = unit + "/";
    Step ex = Make(unit, "extract-silhouette");
    Video(&ex, cam);
    Out(&ex, "-o", dir + "points.csv");
    ex.table = dir + "points.csv";
    Finish(&ex);

    const std::string angles = !st_->theodolite.empty() ? st_->theodolite : st_->turret;
    Step at = Make(unit, "attitude-cylinder");
    Upstream(&at, "--points", ex, dir + "points.csv");
    if (angles.empty()) {
      NotApplicable(&at, "the manifest has no theodolite or turret log");
    } else {
      In(&at, "theodolite", angles);
    }
    In(&at, "camera", cam.model);
    In(&at, "target", cam.target);
    Station(&at, false);
    // The image fit (the frames the points came from) unless "steps" switches it off.
    at.method = at.settings.RunFlag(kImageFitSetting, true) ? "image-fit" : "three-point";
    if (at.method == "image-fit") {
      for (const auto& v : cam.video) In(&at, "video", v);
    }
    Out(&at, "-o", dir + "axis.csv");
    at.table = dir + "axis.csv";
    Finish(&at);
    Plot(at, "axis", dir + "axis.csv", "yaw_deg,pitch_deg", "cylinder axis attitude");
  }

  void Radar(const RadarEntry& r) {
    for (const char* kind : {"register", "register-batch"}) {
      Step s = Make("radar", kind);
      In(&s, "plots", r.plots);
      In(&s, "nav", r.nav);
      const std::string file = std::string("radar/") + (std::string(kind) == "register" ? "biases.csv" : "biases_batch.csv");
      Out(&s, "-o", file);
      s.table = file;
      Finish(&s);
      Plot(s, std::string(kind) == "register" ? "biases" : "biases_batch", file, "", "radar biases");
    }
  }

  // The intersection of a multi-station trial (docs/rk-run.md "Several stations"): rk-intersect on every
  // beacon camera's located target, through the stations.json the plan writes (Step::generated) with each
  // station's position, into trajectory/trajectory.csv.
  void Intersect() {
    const std::string dir = std::string(trial::kTrajectoryUnit) + "/";
    Step s = Make(trial::kTrajectoryUnit, "intersect");
    formats::StationsFile stations;
    auto position = [](const Json& j) {
      return geo::Geodetic{j.at("lat_deg").get<double>(), j.at("lon_deg").get<double>(), j.at("h_m").get<double>()};
    };
    for (const Located& l : located_) {
      const std::string station = l.unit.substr(0, l.unit.find('/'));
      const auto st = std::find_if(m_.stations.begin(), m_.stations.end(),
                                   [&](const trial::StationEntry& e) { return e.name == station; });
      formats::StationSpec spec;
      // rk-intersect's station names are letters, digits, _ . - (SPEC §7): the unit 'S/C' as 'S.C'.
      spec.name = l.unit;
      std::replace(spec.name.begin(), spec.name.end(), '/', '.');
      spec.position = position(st->station);
      spec.located = "../" + l.located;
      stations.stations.push_back(spec);
      const auto from = std::find_if(steps_.begin(), steps_.end(), [&](const Step& x) { return x.id == l.step; });
      Depend(&s, *from);
    }
    if (!m_.origin.is_null()) {
      stations.origin = position(m_.origin);
      stations.origin_given = true;
    }
    const Json j = formats::StationsJson(stations);
    if (located_.size() < 2) {
      NotApplicable(&s, "needs the located targets of two beacon or points cameras, the plan has " +
                            std::to_string(located_.size()));
    }
    s.generated.emplace_back(dir + trial::kStationsFile, j.dump(2) + "\n");
    s.outputs.push_back(dir + trial::kStationsFile);
    Bind(&s, "stations", dir + trial::kStationsFile, true);
    Out(&s, "-o", dir + trial::kTrajectoryFile);
    s.table = dir + trial::kTrajectoryFile;
    Finish(&s);
    Plot(s, "trajectory", s.table, "e_m,n_m,u_m", "trajectory (origin ENU)");
  }

  // The trajectory for viewers of the earth (docs/rk-run.md "Exports: KML and CZML"): rk-export kml and czml into
  // out/trajectory.kml and out/trajectory.czml, with the manifest's epoch_utc and name. What is exported: the
  // intersection's trajectory (several stations), or, in a single-station trial whose manifest gives the station's
  // position and a range log, the located target of its first located camera (beacon or points, in name order:
  // its WGS-84 columns). Any other trial has nothing in WGS-84, and no export step.
  void Export() {
    const Step* from = nullptr;
    std::string table, option;
    if (m_.multi_station()) {
      const auto it = std::find_if(steps_.begin(), steps_.end(), [](const Step& x) { return x.kind == "intersect"; });
      if (it == steps_.end()) return;
      from = &*it;
      table = std::string(trial::kTrajectoryUnit) + "/" + trial::kTrajectoryFile;
      option = "trajectory";
    } else {
      const trial::StationEntry& st = m_.stations.front();
      if (located_.empty() || !st.station.is_object() || st.range.empty()) return;
      const auto it = std::find_if(steps_.begin(), steps_.end(), [&](const Step& x) { return x.id == located_[0].step; });
      from = &*it;
      table = located_[0].located;
      option = "located";
    }
    const Step source = *from;  // steps_ grows below
    for (const auto& [kind, file] : {std::pair<const char*, const char*>{"export-kml", "trajectory.kml"},
                                     std::pair<const char*, const char*>{"export-czml", "trajectory.czml"}}) {
      Step s = Make(trial::kTrajectoryUnit, kind);
      Upstream(&s, option, source, table);
      if (!m_.epoch_utc.empty()) Bind(&s, "epoch-utc", m_.epoch_utc);
      Bind(&s, "name", m_.name);
      Out(&s, "-o", file);
      Finish(&s);
    }
  }

  struct Located {
    std::string unit, located, step;  // camera unit, its located.csv (relative to out/), the locate step
  };
  const TrialManifest& m_;
  const PlanOptions& o_;
  const trial::StationEntry* st_ = nullptr;  // the station being planned (Build)
  std::vector<Located> located_;             // the active locate steps, in plan order
  std::vector<Step> steps_;
};

}  // namespace

std::vector<std::string> OverrideArgs(const StepSettings& settings) {
  std::vector<std::string> out;
  for (const auto& [name, value] : settings.options) {
    if (value.is_boolean()) {
      if (value.get<bool>()) out.push_back("--" + name);
      continue;
    }
    out.push_back("--" + name);
    if (value.is_array()) {
      std::string joined;
      for (const auto& v : value) joined += (joined.empty() ? "" : ",") + ValueText(v);
      out.push_back(joined);
    } else {
      out.push_back(ValueText(value));
    }
  }
  return out;
}

std::vector<Step> BuildPlan(const TrialManifest& manifest, const PlanOptions& options) {
  return PlanBuilder(manifest, options).Build();
}

}  // namespace rk::run
