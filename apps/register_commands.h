// The subcommands of rk-register, one translation unit each (apps/register_<name>_cmd.cpp); rk-register.cpp
// lists them in --help order. Each adds its subcommand to the tool's CLI::App (subcommand.h).
#pragma once

#include "subcommand.h"

namespace rk::app {

Command AddBernoulliCommand(CLI::App& app);  // register_bernoulli_cmd.cpp
Command AddKfCommand(CLI::App& app);         // register_kf_cmd.cpp
Command AddBatchCommand(CLI::App& app);      // register_batch_cmd.cpp

}  // namespace rk::app
