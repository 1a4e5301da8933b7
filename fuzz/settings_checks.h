// The properties the settings fuzzer checks: every value a front end can hand the engine's
// field table or the limits table, as rosparam, dynamic_reconfigure, Python and the CLI
// carry them.
#pragma once

#include <cstddef>
#include <cstdint>
#include <string>

namespace sap_broadphase::fuzz {

/// What the settings fuzzer runs. The first byte picks:
/// - one engine field set from a value of any kind (bool, integer, raw double bits, text):
///   a refusal names the field and leaves the configuration alone; an accepted value lies in
///   the row's range, reads back and passes configProblem (but for the axes rule);
/// - a whole reconfigure request (every field, each value of any kind, applied in order as
///   the node does): when the result is valid, the engine built from it (threads capped at 2)
///   answers two frames as the oracle does (a superset with exact_final_test false);
/// - a row of the limits table and a value: refused exactly outside the row's range.
std::string checkSettingsInput(const uint8_t* inData, std::size_t inSize);

}  // namespace sap_broadphase::fuzz
