// What the rostest gtests share: waiting for a condition no callback signals, and main().
#pragma once

#include <functional>

namespace sap_broadphase {
namespace test {

/// Checks inReady every 50 ms of wall time until it holds, for at most inSeconds; returns
/// whether it held. For conditions that no callback signals (connection counts, a service
/// appearing): the test waits for the condition itself, and inSeconds only keeps a broken
/// system from hanging it. A condition a callback signals is waited for on its
/// condition_variable instead.
bool pollUntil(double inSeconds, const std::function<bool()>& inReady);

/// The main() of a rostest gtest: GoogleTest's flags, ros::init as inNodeName, and the
/// subscriptions' callbacks on an AsyncSpinner of inSpinnerThreads threads while the tests run.
int runRosTests(int argc, char** argv, const char* inNodeName, int inSpinnerThreads);

}  // namespace test
}  // namespace sap_broadphase
