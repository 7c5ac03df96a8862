// The atomic trial folder (sim/trial_folder.h): written in full or not at all, never over an existing one.
#include <gtest/gtest.h>

#include <unistd.h>

#include <filesystem>
#include <fstream>
#include <string>

#include "io/error.h"
#include "sim/trial_folder.h"
#include "rk_test/temp_dir.h"

namespace rk::sim {
namespace {

TEST(TrialFolder, AtomicAndRefusesToOverwrite) {
  namespace fs = std::filesystem;
  const rk::test::TempDir tmp("staged");
  const fs::path base = tmp.path();
  fs::remove_all(base);
  fs::create_directories(base / "keep");
  std::ofstream(base / "keep" / "precious.txt") << "x";
  EXPECT_THROW(TrialFolder((base / "keep").string(), false), Error);
  {
    TrialFolder d((base / "new").string(), false);
    std::ofstream(d.Path("a.txt")) << "a";
    // Destroyed without Commit: nothing appears.
  }
  EXPECT_FALSE(fs::exists(base / "new"));
  {
    TrialFolder d((base / "keep").string(), true);
    std::ofstream(d.Path("b.txt")) << "b";
    d.Commit();
  }
  EXPECT_TRUE(fs::exists(base / "keep" / "b.txt"));
  EXPECT_FALSE(fs::exists(base / "keep" / "precious.txt"));
  std::size_t leftovers = 0;
  for (const auto& e : fs::directory_iterator(base)) leftovers += e.path().filename().string()[0] == '.';
  EXPECT_EQ(leftovers, 0u);
  fs::remove_all(base);
}

}  // namespace
}  // namespace rk::sim
