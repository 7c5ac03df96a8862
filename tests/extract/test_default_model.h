// Shared by the feature tests: the target model of rk-sim attitude's default markers.
#pragma once

#include "sim/attitude_scenario.h"
#include "target/feature_model.h"

namespace rk::extract {

inline target::FeatureModel DefaultModel() {
  target::FeatureModel m;
  m.source = "target.json";
  sim::DefaultAttitudeMarkers(&m.ids, &m.p_body);
  return m;
}

}  // namespace rk::extract
