// The subcommands of rk-analyze, one translation unit each (apps/analyze_<name>_cmd.cpp); rk-analyze.cpp
// lists them in --help order. Each adds its subcommand to the tool's CLI::App (subcommand.h).
#pragma once

#include "subcommand.h"

namespace rk::app {

Command AddCompareCommand(CLI::App& app);  // analyze_compare_cmd.cpp
Command AddBudgetCommand(CLI::App& app);   // analyze_budget_cmd.cpp

}  // namespace rk::app
