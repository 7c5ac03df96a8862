// rk-calibrate's subcommands (apps/subcommand.h).
#pragma once

#include "subcommand.h"

namespace rk::app {

Command AddLensCommand(CLI::App& app);  // calibrate_lens_cmd.cpp

}  // namespace rk::app
