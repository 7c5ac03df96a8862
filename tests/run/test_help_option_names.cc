// run/tools.h HelpOptionNames: the long options a tool's --help lists, CLI11's and argparse's layouts, against
// which rk-run checks a manifest's step options (issue 27: no abbreviation reaches a tool).
#include <gtest/gtest.h>

#include <set>
#include <string>

#include "run/tools.h"

namespace rk::run {
namespace {

TEST(HelpOptionNames, Cli11Layout) {
  const std::string help =
      "Fit the Singer model\n"
      "Usage: rk-smooth singer [OPTIONS]\n\n"
      "Options:\n"
      "  -h,--help                   Print this help message and exit\n"
      "  -i,--input TEXT REQUIRED    Input CSV\n"
      "  --tau FLOAT [5]             Manoeuvre time constant\n"
      "  --bad-rows error|skip [error]  what to do\n"
      "                              -- continuation, not an option\n"
      "Subcommands:\n"
      "  resample                    one series at the times of another\n";
  EXPECT_EQ(HelpOptionNames(help), (std::set<std::string>{"help", "input", "tau", "bad-rows"}));
}

TEST(HelpOptionNames, ArgparseLayout) {
  const std::string help =
      "usage: rk-plot [-h] -i CSV [-o OUTPUT] [--columns COLS]\n\n"
      "options:\n"
      "  -h, --help            show this help message and exit\n"
      "  -i CSV, --input CSV   the table\n"
      "  -o OUTPUT, --output OUTPUT\n"
      "                        the PNG\n"
      "  --columns COLS        columns to plot\n"
      "  --title=TITLE         a title\n";
  const std::set<std::string> names = HelpOptionNames(help);
  EXPECT_EQ(names, (std::set<std::string>{"help", "input", "output", "columns", "title"}));
  EXPECT_EQ(names.count("out"), 0u);  // an abbreviation is not a name
}

}  // namespace
}  // namespace rk::run
