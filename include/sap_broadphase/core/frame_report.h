// What one frame cost and how it was computed (Broadphase::stats()): the path that computed
// it, why its skin is what it is, the sweep axes in force and the time of each phase.
//
// A low floor of the public headers: it includes nothing of the engine. Its fields are one
// table (SAP_FRAME_REPORT_FIELDS) that the struct, Python's `stats`, `sap_pairs --stats` and
// the node's `stats` topic follow.
#pragma once

#include <cstddef>
#include <cstdint>
#include <string>

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
  kNotWorthIt,  ///< automatic: frame too small or too static for a skin to pay, or the
                ///< skin's frames measured dearer than plain ones (a probation)
  kOverBudget,  ///< the skin's grown sweep found more candidates than the memory budget
                ///< (kMaxKeptCandidatesPerBox): none kept, the frame's pairs tested exactly
};

/// Name of a skin choice: "off", "fixed", "first_frame", "ids_changed", "kept", "chosen",
/// "too_fast", "not_worth_it", "over_budget".
const char* skinChoiceName(SkinChoice inChoice);

/// What a report field measures: how front ends write it (an axis by its letter, a path or a
/// skin choice by its name, milliseconds with three decimals).
enum class ReportUnit : uint8_t {
  kCount,         ///< a number of boxes, pairs, threads or slabs
  kAxis,          ///< 0, 1, 2: written x, y, z
  kDispersion,    ///< D of eq. (1) of the paper, unitless
  kFlag,          ///< true / false
  kLength,        ///< in the boxes' units
  kPath,          ///< a FramePath, written by framePathName
  kSkinChoice,    ///< a SkinChoice, written by skinChoiceName
  kMilliseconds,  ///< wall clock
};

/// The report's table: one row per field, X(type, name, default, unit, topic, doc). `name` is
/// the member's, the key of Python's `stats` and the word of `sap_pairs --stats`; `topic` is
/// the sap_broadphase/FrameStats field it is published in (a phase may be folded into a
/// coarser one of the message: the message keeps its fields) or "" when the topic leaves it
/// out. Adding a field is a row here: the struct, the Python dict and the CLI's lines follow,
/// and test_frame_report fails until FrameStats.msg and the node carry a `topic` it names.
// clang-format off
#define SAP_FRAME_REPORT_FIELDS(X) \
  X(std::size_t, boxes, 0, kCount, "boxes", "boxes in the frame") \
  X(std::size_t, boxes_filtered_out, 0, kCount, "", "boxes with group 0 or mask 0: never swept") \
  X(std::size_t, pairs, 0, kCount, "pairs", "pairs reported") \
  X(int, primary_axis, 0, kAxis, "primary_axis", \
    "first sweep axis in force: this frame's sort's, or on a frame without a sort the " \
    "next one's") \
  X(int, secondary_axis, 1, kAxis, "secondary_axis", "second sweep axis in force") \
  X(double, dispersion_primary, 0.0, kDispersion, "dispersion_primary", \
    "D of eq. (1) for this frame's primary-axis sort (0: no sort this frame)") \
  X(double, dispersion_secondary, 0.0, kDispersion, "dispersion_secondary", \
    "D of eq. (1) for this frame's secondary-axis sort") \
  X(bool, axes_swapped, false, kFlag, "axes_swapped", \
    "an axis swap happened after this frame's sort") \
  X(int, threads, 1, kCount, "threads", "threads of this frame") \
  X(int, slabs, 1, kCount, "slabs", \
    "third-axis slabs used by this frame's pairing (1: the single list, or no sweep this " \
    "frame)") \
  X(std::size_t, skin_candidates, 0, kCount, "", "candidate pairs kept by skin reuse") \
  X(std::size_t, static_boxes, 0, kCount, "static_boxes", \
    "boxes of the declared scenery in force") \
  X(double, skin, 0.0, kLength, "skin", "skin of the kept candidates used this frame (0: none)") \
  X(SkinChoice, skin_choice, SkinChoice::kOff, kSkinChoice, "skin_choice", "why that skin") \
  X(std::size_t, moved_boxes, 0, kCount, "moved_boxes", \
    "boxes whose bounds changed since the last frame") \
  X(double, max_displacement, 0.0, kLength, "max_displacement", \
    "largest bound change of one box since the last frame") \
  X(FramePath, path, FramePath::kEmpty, kPath, "path", "the path that computed the frame") \
  X(double, ms_plan, 0.0, kMilliseconds, "ms_history", \
    "the flow itself: dropping boxes that pair with nothing, the plan, learning the " \
    "frame's costs, giving back memory") \
  X(double, ms_history, 0.0, kMilliseconds, "ms_history", \
    "comparing with the last frame and remembering this one") \
  X(double, ms_keys, 0.0, kMilliseconds, "ms_sort", "the sweep's float64 -> sortable keys") \
  X(double, ms_sort, 0.0, kMilliseconds, "ms_sort", \
    "both axes' radix index sorts (keys excluded)") \
  X(double, ms_candidates, 0.0, kMilliseconds, "ms_candidates", \
    "ranks and candidate ranges on the primary axis") \
  X(double, ms_pairing, 0.0, kMilliseconds, "ms_pairing", \
    "secondary sweep and exact overlap tests (the whole work of a small frame or a brute-" \
    "force frame)") \
  X(double, ms_skin, 0.0, kMilliseconds, "ms_pairing", \
    "skin reuse: growing the boxes, keeping the grown sweep's candidates, testing the " \
    "kept candidates, a step of building their successor") \
  X(double, ms_static, 0.0, kMilliseconds, "ms_static", "queries of the declared scenery's index") \
  X(double, ms_output, 0.0, kMilliseconds, "ms_output", \
    "ids, canonical pair order and contact events") \
  X(double, ms_total, 0.0, kMilliseconds, "ms_total", \
    "the whole frame: the phases above add up to it")
// clang-format on

/// What one frame cost and how it was computed: the fields of SAP_FRAME_REPORT_FIELDS. The
/// phases (ms_*) are milliseconds of wall clock, disjoint, and add up to ms_total (up to the
/// timers' own cost).
struct FrameReport {
#define SAP_DECLARE_REPORT_FIELD(type, name, init, unit, topic, doc) type name = init;
  SAP_FRAME_REPORT_FIELDS(SAP_DECLARE_REPORT_FIELD)
#undef SAP_DECLARE_REPORT_FIELD
};

/// One row of the report's table, without its member.
struct ReportField {
  const char* name;   ///< the member's name, Python's key, the CLI's word
  ReportUnit unit;    ///< how it is written
  const char* topic;  ///< its FrameStats field, or "" when the topic leaves it out
  const char* doc;    ///< one line on what it says
};

/// The table's rows, in declaration order.
inline constexpr ReportField kReportFields[] = {
#define SAP_REPORT_FIELD_ROW(type, name, init, unit, topic, doc) \
  ReportField{#name, ReportUnit::unit, topic, doc},
    SAP_FRAME_REPORT_FIELDS(SAP_REPORT_FIELD_ROW)
#undef SAP_REPORT_FIELD_ROW
};

/// Calls inVisit(row, value) for every field of inReport, in the table's order; the value is of
/// the member's own type (std::size_t, int, double, bool, SkinChoice or FramePath).
template <typename Visit>
void forEachReportField(const FrameReport& inReport, Visit&& inVisit) {
#define SAP_VISIT_REPORT_FIELD(type, name, init, unit, topic, doc) \
  inVisit(ReportField{#name, ReportUnit::unit, topic, doc}, inReport.name);
  SAP_FRAME_REPORT_FIELDS(SAP_VISIT_REPORT_FIELD)
#undef SAP_VISIT_REPORT_FIELD
}

/// A field's value as the CLI and logs write it: an axis by its letter, a path or a skin
/// choice by its name, true / false, milliseconds with three decimals, other numbers with six
/// significant digits.
std::string reportValueText(ReportUnit inUnit, double inValue);
std::string reportValueText(ReportUnit inUnit, std::size_t inValue);
std::string reportValueText(ReportUnit inUnit, int inValue);
std::string reportValueText(ReportUnit inUnit, bool inValue);
std::string reportValueText(ReportUnit inUnit, FramePath inValue);
std::string reportValueText(ReportUnit inUnit, SkinChoice inValue);

/// Every field of inReport as "name value" lines, in the table's order (`sap_pairs --stats`).
std::string reportLines(const FrameReport& inReport);

}  // namespace sap_broadphase
