// Unit tests of target::FeatureModel (target/feature_model.h): the checks of the feature-point target model.
#include <gtest/gtest.h>

#include <string>

#include "io/error.h"
#include "io/json_util.h"
#include "target/feature_model.h"

namespace rk::target {
namespace {

// A non-planar 8-marker target about 0.7 m across (the rk-sim attitude layout's scale).
FeatureModel Model() {
  io::Json j = {{"points",
                 {{"nose", {0.40, 0.0, 0.02}},
                  {"tail", {-0.35, 0.0, -0.05}},
                  {"fin", {-0.30, 0.02, -0.25}},
                  {"lwing", {-0.02, -0.36, 0.0}},
                  {"rwing", {-0.08, 0.30, 0.01}},
                  {"belly", {0.12, 0.03, 0.12}},
                  {"ltail", {-0.30, -0.15, 0.0}},
                  {"canopy", {0.22, -0.02, -0.08}}}}};
  return FeatureModelFromJson(j, "target.json");
}

TEST(FeatureModel, RejectsBadModels) {
  auto error_of = [](const io::Json& j) -> std::string {
    try {
      FeatureModelFromJson(j, "t.json");
    } catch (const Error& e) {
      return e.what();
    }
    return "no error";
  };
  EXPECT_NE(error_of({{"length_m", 1.0}}).find("missing field 'points'"), std::string::npos);
  EXPECT_NE(error_of({{"points", {{"a", {0, 0, 0}}, {"b", {1, 0, 0}}, {"c", {0, 1, 0}}}}}).find("at least 4"),
            std::string::npos);
  EXPECT_NE(error_of({{"points", {{"a", {0, 0, 0}}, {"b", {1, 0, 0}}, {"c", {2, 0, 0}}, {"d", {3, 0, 0}}}}})
                .find("collinear"),
            std::string::npos);
  EXPECT_NE(error_of({{"points", {{"a", {0, 0, 0}}, {"b", {1, 0, 0}}, {"c", {0, 1, 0}}, {"d", {1e300, 0, 0}}}}})
                .find("within 10 km"),
            std::string::npos);
  EXPECT_NE(error_of({{"points", {{"a", {0, 0, 0}}, {"b", {1, 0, 0}}, {"c", {0, 1, 0}}, {"d", {0, 0}}}}})
                .find("[x, y, z]"),
            std::string::npos);
  EXPECT_NE(error_of({{"points", {{"a,b", {0, 0, 0}}, {"b", {1, 0, 0}}, {"c", {0, 1, 0}}, {"d", {0, 0, 1}}}}})
                .find("no ','"),
            std::string::npos);
  EXPECT_NE(error_of({{"points", {{"a", {0, 0, 0}}, {"b", {0, 0, 0}}, {"c", {0, 1, 0}}, {"d", {0, 0, 1}}}}})
                .find("coincide"),
            std::string::npos);
  const FeatureModel m = Model();
  EXPECT_EQ(m.Find("nose"), 5);  // belly canopy fin ltail lwing nose ...
  EXPECT_EQ(m.Find("zzz"), -1);
  EXPECT_GT(m.Planarity(), 0.05);
}

}  // namespace
}  // namespace rk::target
