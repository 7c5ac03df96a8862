// io/options.h: one description per option → Check, report keys, CLI11 registration.
#include "io/options.h"

#include <gtest/gtest.h>

#include <cmath>
#include <cstdint>
#include <limits>
#include <string>
#include <vector>

#include "io/cli.h"

namespace rk::io {
namespace {

enum class Mode { kFast, kExact };
std::string ModeName(Mode m) { return m == Mode::kFast ? "fast" : "exact"; }

struct Demo {
  double gap_s = 0.5;
  double ratio = 0.25;
  int window = 3;
  Mode mode = Mode::kExact;

  static const OptionTable<Demo>& Table() {
    static const OptionTable<Demo> table =
        OptionTable<Demo>()
            .Real("--max-gap", &Demo::gap_s, "s", Bounds::Positive(), "Longest gap (s)")
            .Real("--ratio", &Demo::ratio, "", Bounds::LeftOpen(0, 0.5), "A ratio")
            .Integer("--window", &Demo::window, "samples per side", Bounds::Closed(2, 50), "Window")
            .Choice("--mode", &Demo::mode, {Mode::kFast, Mode::kExact}, ModeName, "How");
    return table;
  }
};

TEST(Bounds, ContainsAndDescribe) {
  const double inf = std::numeric_limits<double>::infinity(), nan = std::nan("");
  EXPECT_TRUE(Bounds::Positive().Contains(1e-300));
  EXPECT_FALSE(Bounds::Positive().Contains(0.0));
  EXPECT_FALSE(Bounds::Positive().Contains(nan));
  EXPECT_TRUE(Bounds::Positive().Contains(inf));  // unbounded above: as the hand-written checks were
  EXPECT_FALSE(Bounds::Closed(2, 50).Contains(inf));
  EXPECT_TRUE(Bounds::Closed(2, 50).Contains(50));
  EXPECT_FALSE(Bounds::RightOpen(0, 1).Contains(1));
  EXPECT_TRUE(Bounds::RightOpen(0, 1).Contains(0));
  EXPECT_FALSE(Bounds::AtLeast(1).Contains(-inf));
  // Finite(): infinity refused on the unbounded side as well, and the message says so.
  EXPECT_FALSE(Bounds::Positive().Finite().Contains(inf));
  EXPECT_TRUE(Bounds::Positive().Finite().Contains(1e300));
  EXPECT_FALSE(Bounds::Any().Finite().Contains(-inf));
  EXPECT_EQ(Bounds::Positive().Finite().Describe(), "finite and > 0");
  EXPECT_EQ(Bounds::Any().Finite().Describe(), "a finite number");
  EXPECT_EQ(Bounds::Positive().Describe(), "> 0");
  EXPECT_EQ(Bounds::AtLeast(1).Describe(), ">= 1");
  EXPECT_EQ(Bounds::Closed(2, 50).Describe(), "in [2, 50]");
  EXPECT_EQ(Bounds::LeftOpen(0, 0.5).Describe(), "in (0, 0.5]");
  EXPECT_EQ(Bounds::Open(-1, 1).Describe(), "in (-1, 1)");
}

TEST(ReportKey, FromFlagAndUnit) {
  EXPECT_EQ(ReportKey("--turret-max-gap", "s"), "turret_max_gap_s");
  EXPECT_EQ(ReportKey("--range-window", "samples per side"), "range_window");
  EXPECT_EQ(ReportKey("--search-px", "px"), "search_px");  // the unit is not repeated
  EXPECT_EQ(ReportKey("--turret-interp", ""), "turret_interp");
  EXPECT_EQ(ReportKey("--angle-sigma", "arcsec"), "angle_sigma_arcsec");
}

TEST(OptionTable, CheckNamesTheFlagAndUnit) {
  Demo d;
  std::string why;
  EXPECT_TRUE(d.Table().Check(d, &why));
  d.gap_s = 0;
  EXPECT_FALSE(d.Table().Check(d, &why));
  EXPECT_EQ(why, "--max-gap must be > 0 s");
  d.gap_s = 1;
  d.window = 51;
  EXPECT_FALSE(d.Table().Check(d, &why));
  EXPECT_EQ(why, "--window must be in [2, 50] samples per side");
  d.window = 2;
  d.ratio = std::nan("");
  EXPECT_FALSE(d.Table().Check(d, &why));
  EXPECT_EQ(why, "--ratio must be in (0, 0.5]");
}

TEST(OptionTable, ReportBlockHasEveryOptionUnderItsKey) {
  Demo d;
  d.mode = Mode::kFast;
  const Json j = d.Table().ToJson(d);
  EXPECT_EQ(j.size(), 4u);
  EXPECT_EQ(j.at("max_gap_s").get<double>(), 0.5);
  EXPECT_EQ(j.at("ratio").get<double>(), 0.25);
  EXPECT_EQ(j.at("window").get<int>(), 3);
  EXPECT_EQ(j.at("mode").get<std::string>(), "fast");
}

TEST(OptionTable, CliRegistrationParsesIntoTheMembers) {
  Demo d;
  CLI::App app{"demo", "demo"};
  cli::AddOptions(&app, &d, Demo::Table());
  std::vector<std::string> args = {"exact", "--mode", "7", "--window", "0.1", "--max-gap"};  // reversed
  app.parse(args);
  EXPECT_EQ(d.gap_s, 0.1);
  EXPECT_EQ(d.window, 7);
  EXPECT_EQ(d.mode, Mode::kExact);
  // Defaults shown in --help are the struct's defaults; choices list their names.
  Demo fresh;
  CLI::App app2{"demo", "demo"};
  cli::AddOptions(&app2, &fresh, Demo::Table());
  const std::string help = app2.help();
  EXPECT_NE(help.find("--max-gap FLOAT=0.5"), std::string::npos) << help;
  EXPECT_NE(help.find("--mode TEXT:{fast,exact}=exact"), std::string::npos) << help;
  std::vector<std::string> bad = {"slow", "--mode"};
  EXPECT_THROW(app2.parse(bad), CLI::ValidationError);
}

// Registering keeps a default that its shown text rounds (CLI11's default_val would write "0.498473" back).
struct Fine {
  double sigma_deg = 0.0087 * 180.0 / 3.14159265358979323846;  // 0.4984732818...
  static const OptionTable<Fine>& Table() {
    static const OptionTable<Fine> table =
        OptionTable<Fine>().Real("--sigma", &Fine::sigma_deg, "deg", Bounds::Positive(), "Sigma (deg)");
    return table;
  }
};

TEST(OptionTable, CliRegistrationKeepsADefaultItsHelpRounds) {
  Fine f;
  const double exact = f.sigma_deg;
  CLI::App app{"demo", "demo"};
  cli::AddOptions(&app, &f, Fine::Table());
  EXPECT_EQ(f.sigma_deg, exact);
  std::vector<std::string> none;
  app.parse(none);
  EXPECT_EQ(f.sigma_deg, exact);
  EXPECT_NE(app.help().find("--sigma FLOAT=0.498473"), std::string::npos) << app.help();
}

// A nested struct's table composes into the outer one (Sub), with switches, 64-bit counts and aliases.
struct Inner {
  double speed_mps = 2.0;
  bool loud = false;
  static const OptionTable<Inner>& Table() {
    static const OptionTable<Inner> table = OptionTable<Inner>()
                                                .Real("--speed", &Inner::speed_mps, "m/s", Bounds::Positive(), "Speed")
                                                .Flag("--loud", &Inner::loud, "Say more")
                                                .Alias("-l");
    return table;
  }
};

struct Outer {
  std::uint64_t seed = 7;
  Inner inner;
  static const OptionTable<Outer>& Table() {
    static const OptionTable<Outer> table =
        OptionTable<Outer>()
            .Count("--seed", &Outer::seed, "", Bounds::Any(), "Random seed")
            .Sub(&Outer::inner, Inner::Table());
    return table;
  }
};

TEST(OptionTable, NestedTablesFlagsCountsAndAliases) {
  Outer o;
  CLI::App app{"demo", "demo"};
  cli::AddOptions(&app, &o, Outer::Table());
  std::vector<std::string> args = {"-l", "3.5", "--speed", "18446744073709551615", "--seed"};  // reversed
  app.parse(args);
  EXPECT_EQ(o.seed, 18446744073709551615ull);
  EXPECT_EQ(o.inner.speed_mps, 3.5);
  EXPECT_TRUE(o.inner.loud);
  const Json j = Outer::Table().ToJson(o);
  EXPECT_EQ(j.at("seed").get<std::uint64_t>(), 18446744073709551615ull);
  EXPECT_EQ(j.at("speed").get<double>(), 3.5);
  EXPECT_EQ(j.at("loud").get<bool>(), true);
  std::string why;
  EXPECT_TRUE(Outer::Table().Check(o, &why));
  o.inner.speed_mps = -1.0;
  EXPECT_FALSE(Outer::Table().Check(o, &why));
  EXPECT_EQ(why, "--speed must be > 0 m/s");
  // Flags take no value; the alias shows in --help.
  Outer fresh;
  CLI::App app2{"demo", "demo"};
  cli::AddOptions(&app2, &fresh, Outer::Table());
  EXPECT_NE(app2.help().find("-l,--loud"), std::string::npos) << app2.help();
  std::vector<std::string> bad = {"yes", "--loud"};
  EXPECT_THROW(app2.parse(bad), CLI::ParseError);
}

// Options registered by hand between table options keep their place in --help: the hook for a flag runs
// just before that table option is registered.
TEST(OptionTable, HandOptionsBetweenTableOptionsKeepTheHelpOrder) {
  Demo d;
  std::string path;
  CLI::App app{"demo", "demo"};
  cli::AddOptions(&app, &d, Demo::Table(), {{"--window", [&] { app.add_option("--path", path, "A file"); }}});
  std::vector<std::string> names;
  for (const CLI::Option* o : app.get_options()) {
    if (o->get_lnames().size() == 1) names.push_back("--" + o->get_lnames()[0]);
  }
  const std::vector<std::string> want = {"--help", "--max-gap", "--ratio", "--path", "--window", "--mode"};
  EXPECT_EQ(names, want);
  std::vector<std::string> args = {"f.csv", "--path", "5", "--window"};  // reversed
  app.parse(args);
  EXPECT_EQ(path, "f.csv");
  EXPECT_EQ(d.window, 5);
}

}  // namespace
}  // namespace rk::io
