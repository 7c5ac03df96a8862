// rk-sim theodolite's trial files (sim/theodolite_trial.h): written atomically.
#include <gtest/gtest.h>

#include <filesystem>
#include <fstream>

#include "io/csv.h"
#include "io/error.h"
#include "sim/theodolite_scene.h"
#include "sim/theodolite_trial.h"
#include "rk_test/temp_dir.h"

namespace rk::sim {
namespace {

TEST(TheodoliteTrial, WritesTheFilesAtomically) {
  namespace fs = std::filesystem;
  const rk::test::TempDir tmp("theodolite_trial");
  const fs::path dir = fs::path(tmp.path()) / "trial";
  fs::remove_all(dir);
  TheodoliteSimOptions o;
  o.duration_s = 0.1;
  o.quantise = true;
  TheodoliteWriteOptions w;
  w.out_dir = dir.string();
  const TheodoliteSimulator sim(o);
  const TheodoliteTrialSummary s = WriteTheodoliteTrial(sim, w);
  EXPECT_EQ(s.frames, 3);
  for (const char* f : {"trial.json", "target.json", "theodolite.csv", "points.csv", "theo/camera.json",
                        "theo/frames.csv", "truth/axis.csv", "truth/points.csv", "truth/theodolite.csv"}) {
    EXPECT_TRUE(fs::exists(dir / f)) << f;
  }
  const io::CsvTable pts = io::CsvTable::Read((dir / "points.csv").string());
  EXPECT_EQ(pts.rows(), 9u);
  EXPECT_EQ(pts.Cell(1, pts.RequireColumn("id")), "tail1");
  // Refuses a non-empty folder without force, and leaves it as it was.
  EXPECT_THROW(WriteTheodoliteTrial(sim, w), Error);
  EXPECT_TRUE(fs::exists(dir / "points.csv"));
  fs::remove_all(dir);
}

}  // namespace
}  // namespace rk::sim
