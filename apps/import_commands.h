// rk-import's subcommands (apps/subcommand.h): real recordings and records into rangekit's files.
#pragma once

#include "subcommand.h"

namespace rk::app {

Command AddFramesCommand(CLI::App& app);   // import_frames_cmd.cpp
Command AddAsterixCommand(CLI::App& app);  // import_asterix_cmd.cpp

}  // namespace rk::app
