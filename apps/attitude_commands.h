// The subcommands of rk-attitude, one translation unit each (apps/attitude_<name>_cmd.cpp); rk-attitude.cpp
// lists them in --help order. Each adds its subcommand to the tool's CLI::App (subcommand.h).
#pragma once

#include "subcommand.h"

namespace rk::app {

Command AddCylinderCommand(CLI::App& app);  // attitude_cylinder_cmd.cpp
Command AddOiCommand(CLI::App& app);        // attitude_oi_cmd.cpp

}  // namespace rk::app
