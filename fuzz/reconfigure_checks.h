// The properties the reconfigure fuzzer checks (dynamic_reconfigure requests as the node's
// server hands them over), shared with the replay test. Needs the ROS layer
// (src/ros/node_params.cpp) and the header generated from cfg/BroadphaseNode.cfg, no roscore.
#pragma once

#include <cstddef>
#include <cstdint>
#include <string>

namespace sap_broadphase::fuzz {

/// What the reconfigure fuzzer runs: up to three requests in a row, each a
/// dynamic_reconfigure::Config of entries decoded from the bytes (any parameter of the .cfg,
/// mostly of its own kind, sometimes of another kind or an unknown name; integers, raw double
/// bits, edge values, text). Each goes through what dynamic_reconfigure's server does
/// (__fromMessage__ over the settings in force, __clamp__) and then the node's check,
/// fromReconfigureConfig, as NodeReconfigure calls it:
/// - a refusal leaves the settings in force untouched and names the parameter;
/// - accepted settings pass configProblem() and the limits table's rows, the config written
///   back to the client (toReconfigureConfig) is accepted again unchanged, and the engine
///   built from them (threads capped at 2) answers a frame as the oracle does (a superset with
///   exact_final_test false).
/// Nothing may throw.
std::string checkReconfigureInput(const uint8_t* inData, std::size_t inSize);

}  // namespace sap_broadphase::fuzz
