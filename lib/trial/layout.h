// Names and columns of the files of a trial directory (SPEC.md §6), written by rk-capture and rk-sim and read
// by rk-run and `rk-capture recover` (docs/rk-capture.md, docs/rk-run.md). Paths in the manifest are relative
// to the trial folder; a camera's files sit in a folder named after the camera (CameraFile).
#pragma once

#include <string>

namespace rk::trial {

inline constexpr const char* kManifestFile = "trial.json";
inline constexpr const char* kEventsFile = "events.log";
inline constexpr const char* kRangeFile = "range.csv";
inline constexpr const char* kTurretFile = "turret.csv";
inline constexpr const char* kTheodoliteFile = "theodolite.csv";
inline constexpr const char* kRadarPlotsFile = "plots.csv";
inline constexpr const char* kRadarNavFile = "nav.csv";
inline constexpr const char* kFramesFile = "frames.csv";  // in each camera's folder
inline constexpr const char* kCameraModelFile = "camera.json";
inline constexpr const char* kTargetModelFile = "target.json";
inline constexpr const char* kPointingFile = "pointing.json";  // the station's turret pointing model (SPEC.md §3.1)
// A multi-station trial's intersection (docs/rk-run.md "Several stations"): rk-run's unit and folder in out/
// (so no station may have this name), the stations.json it writes there for rk-intersect, and the trajectory.
inline constexpr const char* kTrajectoryUnit = "trajectory";
inline constexpr const char* kStationsFile = "stations.json";
inline constexpr const char* kTrajectoryFile = "trajectory.csv";
// Held (flock) by rk-capture while it records into the folder; the kernel releases it when the
// process ends, even by kill -9. `recover` refuses a folder whose lock is held.
inline constexpr const char* kCaptureLockFile = ".rk-capture.lock";

// "<camera>/<file>": a file of a camera's folder, as the manifest names it.
inline std::string CameraFile(const std::string& camera, const char* file) { return camera + "/" + file; }

// frame: 0-based decode index over all segments; seq: the source's frame counter (a jump = frames
// dropped before the disk); segment: index of the segment holding the frame.
inline constexpr const char* kFramesColumns = "frame,t_s,host_mono_s,host_real_s,seq,segment";
// status: 0 ok, else the device's error code (range empty).
inline constexpr const char* kRangeColumns = "t_s,range_m,status,host_mono_s,host_real_s";
inline constexpr const char* kTurretColumns =
    "t_s,az_deg,el_deg,pan_pos,tilt_pos,pan_res_arcsec,tilt_res_arcsec,pair_dt_s,host_mono_s,host_real_s";

}  // namespace rk::trial
