// Known-association Kalman filter baseline for radar bias registration (seed 002's comparison
// method, Chen et al., J. Navigation 2014): the same measurement model (radar_model.h) and random
// walk (filter_common.h), updated each step with the pairs whose plots carry the same track_id
// in both radars (sequentially, Joseph form). No gating: the association is given. A pair whose
// d² exceeds the chi-square 0.999 bound is still used but counted (a sign of a wrong track_id or
// of the model not fitting). Pairs with a 2-D plot update with the reduced pair (radar_model.h), fewer dof.
// track = "all": every common target (centralised, the best a known association can do);
// track = <id>: that target only (the paper's Figs. 1–2 show one such filter per target).
#pragma once

#include <functional>
#include <string>
#include <utility>
#include <vector>

#include "registration/filter_common.h"
#include "registration/input.h"

namespace rk::registration {

struct KfOptions {
  FilterOptions filter;
  std::string track = "all";  // "all" or one track_id value of the plots file
  bool Check(std::string* why) const;
  io::Json ToJson() const;
};

struct KfResult {
  RegistrationResult result;
  std::vector<std::vector<std::pair<int, int>>> used;  // per step, the pairs used
  FilterCounters counters;
  std::int64_t large_innovations = 0;  // pairs with d² > the chi-square 0.999 quantile of their dimension (3 dof: 16.27)
  double mean_nis = 0.0;               // mean d² over the updates (mean_dof when consistent)
  double mean_dof = 0.0;               // mean dimension of the updates: 3, less with 2-D plots (radar_model.h)
};

// Throws DataError if the plots have no track_id column, UsageError if `track` names no track.
// `progress(k)` (optional) is called after each of the input's steps, k = steps done.
KfResult RunKalman(const RegistrationInput& input, const KfOptions& options,
                   const std::function<void(std::int64_t)>& progress = {});

}  // namespace rk::registration
