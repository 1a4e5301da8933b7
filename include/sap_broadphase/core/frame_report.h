// What one frame cost and how it was computed (Broadphase::stats()): the path that computed
// it, why its skin is what it is, the sweep axes in force and the time of each phase.
//
// A low floor of the public headers: it includes nothing of the engine.
#pragma once

#include <cstddef>
#include <cstdint>

namespace sap_broadphase {

/// Which path computed a frame.
enum class FramePath : uint8_t {
  kEmpty,       ///< fewer than two boxes take part
  kSequential,  ///< Algorithm 1
  kParallel,    ///< Algorithms 2, 3, 4
  kBruteForce,  ///< the oracle
  kReused,      ///< same boxes as the previous frame: its pairs returned without a sweep
  kSkin,        ///< every box inside its skin: the kept candidates tested, no sweep
  kSmallFrame,  ///< the small-frame kernel (small_frame.h): frames below parallel_min_boxes
                ///< (one thread), and every frame of Method::kAuto on one or two threads
};

/// Human-readable name of a path: "empty", "sequential", "parallel", "brute", "reused", "skin",
/// "small".
const char* framePathName(FramePath inPath);

/// Why the skin in force for a frame is what it is.
enum class SkinChoice : uint8_t {
  kOff,         ///< configured off (skin = 0)
  kFixed,       ///< the configured fixed skin
  kFirstFrame,  ///< automatic: no previous frame to measure motion against, plain sweep
  kIdsChanged,  ///< automatic: ids or their order changed, motion unknown, plain sweep
  kKept,        ///< automatic: every box still inside the skin of the last sweep
  kChosen,      ///< automatic: a new skin chosen from the measured motion and costs
  kTooFast,     ///< automatic: at the measured motion no skin beats a plain sweep
  kNotWorthIt,  ///< automatic: frame too small or too static for a skin to pay
  kOverBudget,  ///< the skin's grown sweep found more candidates than the memory budget
                ///< (kMaxKeptCandidatesPerBox): none kept, the frame's pairs tested exactly
};

/// Name of a skin choice: "off", "fixed", "first_frame", "ids_changed", "kept", "chosen",
/// "too_fast", "not_worth_it", "over_budget".
const char* skinChoiceName(SkinChoice inChoice);

/// What one frame cost and how it was computed. Times are milliseconds of wall clock.
struct FrameReport {
  std::size_t boxes = 0;
  std::size_t boxes_filtered_out = 0;  ///< boxes with group 0 or mask 0: never swept
  std::size_t pairs = 0;
  /// The sweep axes in force: those this frame's sort used, or on a frame without a sort
  /// those the next sort will use (the configured axes until section 5 swaps one).
  int primary_axis = 0;
  int secondary_axis = 1;
  double dispersion_primary = 0.0;    ///< D of eq. (1) for this frame's primary-axis sort
                                      ///< (0: no sort this frame)
  double dispersion_secondary = 0.0;  ///< D of eq. (1) for this frame's secondary-axis sort
  bool axes_swapped = false;          ///< an axis swap happened after this frame's sort
  int threads = 1;
  int slabs = 1;                    ///< third-axis slabs used by this frame's pairing (1: the
                                    ///< single list, or no sweep this frame)
  std::size_t skin_candidates = 0;  ///< candidate pairs kept by skin reuse
  std::size_t static_boxes = 0;     ///< boxes of the declared scenery in force
  double skin = 0.0;                ///< skin of the kept candidates used this frame (0: none)
  SkinChoice skin_choice = SkinChoice::kOff;  ///< why that skin
  std::size_t moved_boxes = 0;                ///< boxes whose bounds changed since the last frame
  double max_displacement = 0.0;  ///< largest bound change of one box since the last frame
  FramePath path = FramePath::kEmpty;
  // Phases, in milliseconds of wall clock. They are disjoint and add up to ms_total (up to the
  // timers' own cost).
  double ms_plan = 0.0;        ///< the flow itself: dropping boxes that pair with nothing, the
                               ///< plan, learning the frame's costs, giving back memory
  double ms_history = 0.0;     ///< comparing with the last frame and remembering this one
  double ms_keys = 0.0;        ///< the sweep's float64 -> sortable keys
  double ms_sort = 0.0;        ///< both axes' radix index sorts (keys excluded)
  double ms_candidates = 0.0;  ///< ranks and candidate ranges on the primary axis
  double ms_pairing = 0.0;     ///< secondary sweep and exact overlap tests (the whole work of a
                               ///< small frame or a brute-force frame)
  double ms_skin = 0.0;        ///< skin reuse: growing the boxes, keeping the grown sweep's
                               ///< candidates, testing the kept candidates
  double ms_static = 0.0;      ///< queries of the declared scenery's index
  double ms_output = 0.0;      ///< ids, canonical pair order and contact events
  double ms_total = 0.0;
};

}  // namespace sap_broadphase
