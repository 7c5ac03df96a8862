// The subcommands of rk-sim, one translation unit each (apps/sim_<name>_cmd.cpp); rk-sim.cpp lists
// them in --help order. Each adds its subcommand to the tool's CLI::App (subcommand.h).
#pragma once

#include "subcommand.h"

namespace rk::app {

Command AddBeaconCommand(CLI::App& app);      // sim_beacon_cmd.cpp
Command AddPosetrackCommand(CLI::App& app);   // sim_posetrack_cmd.cpp
Command AddTheodoliteCommand(CLI::App& app);  // sim_theodolite_cmd.cpp
Command AddAttitudeCommand(CLI::App& app);    // sim_attitude_cmd.cpp
Command AddRadarCommand(CLI::App& app);       // sim_radar_cmd.cpp
Command AddDeviceCommand(CLI::App& app);      // sim_device_cmd.cpp
Command AddMultistationCommand(CLI::App& app);  // sim_multistation_cmd.cpp
Command AddPointingCommand(CLI::App& app);    // sim_pointing_cmd.cpp
Command AddPointsCommand(CLI::App& app);      // sim_points_cmd.cpp

}  // namespace rk::app
