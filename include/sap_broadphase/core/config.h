// What a caller may tune, and the one description of it: every field of BroadphaseConfig with
// its name, type, default, allowed values and meaning, in one table (configFields()). The
// engine checks a configuration against the table (configProblem); front ends (the ROS node's
// parameters, dynamic_reconfigure, its start-up log) walk the same table, so adding a field is
// one row here and one member in the struct.
//
// The lowest floor of the public headers: it includes nothing of the engine.
#pragma once

#include <cstddef>
#include <cstdint>
#include <iterator>
#include <optional>
#include <string>
#include <variant>
#include <vector>

namespace sap_broadphase {

/// Which algorithm computes a frame.
enum class Method : uint8_t {
  kAuto,      ///< one thread below BroadphaseConfig::parallel_min_boxes; the small-frame kernel on
              ///< up to 2 threads, the parallel sweep on more
  kParallel,  ///< Algorithms 2, 3 and 4 of the paper
  kSequential,  ///< Algorithm 1 of the paper
  kBruteForce,  ///< all pairs tested (the oracle); for checks and tiny frames
};

/// Every method, in the order of the vocabulary below.
inline constexpr Method kMethods[] = {Method::kAuto, Method::kParallel, Method::kSequential,
                                      Method::kBruteForce};

/// The one vocabulary of method names: "auto", "parallel", "sequential", "brute".
const char* methodName(Method inMethod);
/// Parses a method name; "sap" is accepted for "auto" (the CLI's name for it). Nothing when
/// the name is unknown.
std::optional<Method> parseMethod(const std::string& inName);
/// The names of inMethods as a list for messages: "auto, parallel, sequential or brute";
/// inName spells each one (a front end with names of its own passes its speller).
std::string methodList(const std::vector<Method>& inMethods = {std::begin(kMethods),
                                                               std::end(kMethods)},
                       const char* (*inName)(Method) = methodName);

/// Name of a sweep axis: "x", "y" or "z" ("?" out of range).
const char* axisName(int inAxis);
/// Parses an axis given as x, y, z (either case) or 0, 1, 2. Nothing otherwise.
std::optional<int> parseAxis(const std::string& inText);

/// The skin as text: "auto" (nothing), "off" (0) or the shortest decimal that reads back as
/// the same double (so that a skin written to a parameter server and read back is the same).
std::string skinToText(const std::optional<double>& inSkin);
/// Parses "auto" (or empty), "off" or a number (strtod, whole text) into outSkin. The range is
/// configProblem's to check.
bool skinFromText(const std::string& inText, std::optional<double>& outSkin);

/// Most worker threads a processor (BroadphaseConfig::threads): the sweep's passes meet at a
/// barrier each, so threads beyond the processors only wait there for a core, and OpenMP
/// starts every one of them (999 on two cores took 110 s against 0.25 s; 100000 exhausts the
/// address space). Four a processor leaves room for oversubscribed runs and hyper-threads.
constexpr int kMaxThreadsPerProcessor = 4;
/// Most threads any entry point accepts on this machine: kMaxThreadsPerProcessor times
/// omp_get_num_procs().
int maxThreads();

/// Largest skin (BroadphaseConfig::skin): the grown boxes' sort keys are float32, so a skin
/// past float32's range grows every key to infinity. What a skin below it may cost in kept
/// candidates is bounded separately (kMaxKeptCandidatesPerBox, skin_list.h).
constexpr double kMaxSkin = 3.0e38;

/// Most third-axis slabs (BroadphaseConfig::third_axis_slabs): slab numbers are stored in 8
/// bits, and more slabs cost inserts for large boxes.
constexpr int kMaxThirdAxisSlabs = 64;

/// Default bound on a frame's pairs (BroadphaseConfig::max_pairs): 2^28 pairs are 2 GiB in
/// each list of them, and a frame holds a few such lists (the pairing threads', the sorted
/// list, the last frame's for the events; in the node the PairArray message too).
constexpr std::size_t kDefaultMaxPairs = std::size_t{1} << 28;

/// What a caller may tune. Defaults are the exact, adaptive engine.
struct BroadphaseConfig {
  int threads = 0;                    ///< worker threads; 0 = all cores (omp_get_max_threads)
  Method method = Method::kAuto;      ///< algorithm choice
  int primary_axis = 0;               ///< first sweep axis (0 = x, 1 = y, 2 = z)
  int secondary_axis = 1;             ///< second sweep axis; must differ from primary_axis
  bool axis_swapping = true;          ///< swap a clustered sweep axis with the unused one (§5)
  double axis_swap_threshold = 0.25;  ///< dispersion D above which an axis is swapped
  std::size_t parallel_min_boxes = 32768;  ///< kAuto: frames below this many boxes run on one
                                           ///< thread, the small-frame path (or the sequential
                                           ///< sweep under a fixed skin); measured crossover
  int third_axis_slabs = 0;                ///< active lists per slab of the unused axis: 0 = auto,
                                           ///< 1 = the paper's single list, k = k slabs (max 64)
  bool reuse_unchanged_frames = true;      ///< a frame bit for bit equal to the previous one
                                           ///< (ids, bounds, groups, masks) returns its pairs; the
                                           ///< comparison is the frame history's, done anyway
  /// Skin reuse (kept candidates): sweep boxes grown by skin / 2 a side, then test only those
  /// candidates until a box leaves its grown box. Nothing (the default) = automatic: chosen
  /// each sweep from the measured motion and costs, off when it does not pay; 0 = off;
  /// > 0 = this fixed skin.
  std::optional<double> skin;
  /// false: the sweeps skip their exact float64 test and report every pair whose
  /// outward-rounded float32 keys overlap: a superset of the exact pairs, never missing one.
  /// That holds where a sweep answers the frame without a skin: Method::kParallel and
  /// kSequential, and kAuto at or above parallel_min_boxes with more than two threads. The
  /// other paths test in doubles whatever this says and return the exact pairs: kAuto's
  /// small-frame path (below parallel_min_boxes, or up to two threads), kept candidates (a skin),
  /// brute force. So a frame may bring extra pairs or none, depending on its path.
  bool exact_final_test = true;
  /// Most pairs a frame may have: a frame with more is refused (update() throws TooManyPairs)
  /// instead of holding pairs until memory runs out. The sweeps and the small-frame kernel
  /// stop once past it (holding the bound and a chunk of 8192 pairs a thread at most); brute
  /// force, the kept candidates' answer and the pairs with the scenery are checked once found.
  /// A sweep of boxes grown by a skin counts its candidates, a superset of the pairs: with a
  /// bound near the frame's pair count, a skin can have a frame refused that would pass
  /// without one.
  std::size_t max_pairs = kDefaultMaxPairs;
};

/// The kinds of value a configuration field holds.
enum class ConfigFieldType : uint8_t {
  kBool,     ///< true / false
  kInteger,  ///< a whole number in [min, max]
  kNumber,   ///< a real number in [min, max]
  kMethod,   ///< a method name (methodName)
  kAxis,     ///< an axis: x, y, z (or 0, 1, 2)
  kSkin,     ///< auto, off (or 0) or a skin in [0, kMaxSkin]
};

/// A field's value as front ends carry it: kBool as bool, kInteger as int64_t, kNumber as
/// double, kMethod, kAxis and kSkin as their text (methodName, axisName, skinToText).
using ConfigValue = std::variant<bool, int64_t, double, std::string>;

/// One row of the table: everything a front end needs to load, offer, log or check a field.
struct ConfigField {
  const char* name;  ///< the member's name, also the ROS parameter's
  ConfigFieldType type;
  const char* default_text;  ///< the default, as valueText() writes it
  double min;                ///< kInteger, kNumber: smallest allowed value
  double max;                ///< kInteger, kNumber: largest allowed value (may be +inf)
  const char* allowed;       ///< what may be given, for messages: "an integer >= 0 (0 = all cores)"
  const char* doc;           ///< one line on what it does
  const char* reason;        ///< why the range is what it is (docs/ROBUSTNESS.md, "Limits")
  /// The field's value in inConfig.
  ConfigValue (*get)(const BroadphaseConfig& inConfig);
  /// Stores inValue into ioConfig when it is of an accepted kind and in range (an integer is
  /// accepted for a number, an integral number for an integer, a number or an integer for an
  /// axis or a skin); otherwise leaves ioConfig alone and says what is wrong.
  std::optional<std::string> (*set)(BroadphaseConfig& ioConfig, const ConfigValue& inValue);
};

/// The table: one row per field of BroadphaseConfig, in declaration order.
const std::vector<ConfigField>& configFields();
/// The row named inName, or nullptr.
const ConfigField* findConfigField(const std::string& inName);
/// A value as text: "true", "12288", "0.25", "x", "auto".
std::string valueText(const ConfigValue& inValue);
/// Every field as "name value", comma-separated (a start-up log line).
std::string describeConfig(const BroadphaseConfig& inConfig);
/// True when every field of inA equals the same field of inB.
bool sameConfig(const BroadphaseConfig& inA, const BroadphaseConfig& inB);

/// Number of threads that `inRequested` (0 = all cores, as BroadphaseConfig::threads)
/// resolves to.
int resolveThreadCount(int inRequested);

/// What is wrong with inConfig, in words a user can act on, or nothing when it is valid: every
/// field against its row of the table, then the rules between fields (distinct axes). The one
/// check of a configuration (the engine's constructor and the node both use it).
std::optional<std::string> configProblem(const BroadphaseConfig& inConfig);

// ---- The limits table: every numeric value any entry point takes ----
//
// Beside the engine's fields (configFields(), the same rows for rosparam, dynamic_reconfigure
// and Python keywords), the node's own parameters, the CLI flags, the text reader and the
// message sizes: each with its closed range, why, and what a value outside it gets. Every
// entry point checks its values here (limitProblem) and refuses, never clamps;
// docs/ROBUSTNESS.md ("Limits of every entry point") is this table (limitsMarkdown()), and a
// test fails when the two differ.

/// Longest line the box text reader takes (bytes, newline excluded): a box line is at most
/// about 200 bytes; the rest leaves room for comments. Checked while reading, so that an
/// endless line (`sap_pairs /dev/zero`) is refused after this many bytes.
constexpr std::size_t kMaxTextLineBytes = std::size_t{1} << 20;

/// Most hits one query may answer (Broadphase::query, the node's query_boxes): 2^24 hits are
/// 128 MB while found and as many again in the answer (and in a query_boxes response, 8 bytes
/// a hit). Past it the query is refused (std::length_error naming the count) instead of
/// holding hits until memory runs out: a frame scan stops once the bound is passed, the
/// frame's index and the scenery are refused once their hits are found.
constexpr std::size_t kMaxQueryHits = std::size_t{1} << 24;

/// One numeric value an entry point takes.
struct Limit {
  const char* entry;      ///< where it comes in: "node parameter", "sap_pairs", ...
  const char* name;       ///< as that entry point spells it: "~rate", "--threads"
  double min;             ///< smallest valid value (closed range)
  double max;             ///< largest valid value (may be +inf)
  bool zero_allowed;      ///< 0 (off, all, none) is valid besides [min, max]
  const char* allowed;    ///< what may be given, for messages and the doc
  const char* reason;     ///< why the range is what it is
  const char* violation;  ///< what a value outside it gets
};

/// Every limit of every entry point; the engine's fields first (one row each, taken from
/// configFields(), that rosparam, dynamic_reconfigure and Python share).
const std::vector<Limit>& limits();
/// The row of inName at inEntry (inName as the entry point spells it), or nullptr.
const Limit* findLimit(const std::string& inEntry, const std::string& inName);
/// "NAME must be ALLOWED, not VALUE" when inValue is outside inLimit (NaN included), or nothing.
std::optional<std::string> limitProblem(const Limit& inLimit, double inValue);
/// The table as Markdown rows for docs/ROBUSTNESS.md.
std::string limitsMarkdown();

}  // namespace sap_broadphase
