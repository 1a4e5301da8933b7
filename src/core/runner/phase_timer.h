// Wall-clock time of the phases of one frame: one scoped timer adds its lifetime to one field
// of the FrameReport, so every field means exactly the code its scope covers.
#pragma once

#include <chrono>

namespace sap_broadphase {

using Clock = std::chrono::steady_clock;

/// Milliseconds since inStart.
inline double millisecondsSince(Clock::time_point inStart) {
  return std::chrono::duration<double, std::milli>(Clock::now() - inStart).count();
}

/// Adds the milliseconds between its construction and destruction to ioField.
class PhaseTimer {
 public:
  explicit PhaseTimer(double& ioField) : field_(ioField), start_(Clock::now()) {}
  ~PhaseTimer() { field_ += millisecondsSince(start_); }
  PhaseTimer(const PhaseTimer&) = delete;
  PhaseTimer& operator=(const PhaseTimer&) = delete;

 private:
  double& field_;
  Clock::time_point start_;
};

}  // namespace sap_broadphase
