// The engine's tuning constants, each with the reason for its value. None of them affects
// which pairs are reported, only how fast they are found and how much memory is kept.
#pragma once

#include <cstddef>
#include <cstdint>

namespace sap_broadphase::tuning {

// ---- Sweep (Algorithms 2-4) ----

/// Sort partitions (m of Algorithm 2). More partitions than threads keeps each one
/// cache-sized and gives the dispersion D a grain fine enough to notice clustering (§5);
/// they are handed out to threads dynamically.
constexpr int kSortPartitions = 16;
/// Below this many endpoints one partition is cheaper than bucketing into m of them.
constexpr std::size_t kMinPartitionedEndpoints = 8192;
/// Below this many items a comparison sort beats clearing the radix sort's three 2048-entry
/// histograms.
constexpr std::size_t kSmallIndexSort = 256;
/// Endpoints between the prefetch of a box's record and its use, in every pass that reads the
/// records in sweep order, i.e. at random (candidate ranges, the pairing scatter, the pairing
/// sweep): enough to cover a miss to memory at a few nanoseconds an endpoint.
constexpr std::size_t kEndpointPrefetchAhead = 16;
/// Largest rank partition of the parallel pairing (Algorithm 4): its slab trees stay
/// cache-resident. Ranks inside it must fit the 16 bits of a pairing entry (static_assert in
/// sweep_pairing.cpp).
constexpr uint32_t kPairingPartitionRanks = 1u << 15;
/// Fewest rank partitions per thread of the parallel pairing (when there are several threads):
/// enough that handing them out by decreasing work evens the threads out.
constexpr uint32_t kPairingPartitionsPerThread = 4;
/// Largest total size, in bits (n ranks times the slab count), of the whole-stream trees that
/// the one-thread pairing sweeps with; above it the thread sweeps rank partitions instead.
/// Measured on the uniform scene (d = 0.35, 1 thread): whole-stream trees win by 5-10% up to
/// 2^18 boxes (46 slabs, 1.5 MiB of trees), partitions by a third from 2^19 boxes (58 slabs,
/// 3.6 MiB), where every insert, erase and range walk on the big trees misses the cache.
constexpr uint64_t kSequentialTreeBits = uint64_t{1} << 24;
/// Candidates the pairing's branch-free key filter collects before the exact tests (a stack
/// buffer): large enough to amortise the switch between the two loops, small enough for L1.
constexpr uint32_t kSurvivorBlock = 64;
/// Room a scatter segment gets beyond its size in the last frame, as a share (1 / this) plus
/// a constant: coherent frames change each segment's size by a few percent at most.
constexpr std::size_t kSegmentRoomShare = 16;
constexpr std::size_t kSegmentRoomEntries = 64;

// ---- Third-axis slab active lists (slab_grid.h) ----

/// Below this many boxes one active list is as fast as any split.
constexpr std::size_t kMinBoxesForSlabs = 2048;
/// Slab width in mean box extents: wider slabs mean more candidates per query, narrower ones
/// mean boxes sit in more trees.
constexpr double kSlabWidthInExtents = 2.0;

// ---- Static index of the declared scenery (static_index.h) ----

/// Cell edge in mean box extents. At one extent a box covers about 2^3 cells and a cell holds
/// about density * 8 boxes; the cap below usually decides instead.
constexpr double kCellInExtents = 1.0;
/// Most cells per indexed box: bounds the offsets array (8 bytes a cell) and empty-cell visits.
constexpr double kCellsPerBox = 1.0;
/// A box covering more cells than this goes to the large list: listing it in every cell would
/// cost more memory and cell visits than testing it against each query.
constexpr uint64_t kMaxCellsPerBox = 64;
/// Queries ahead whose cell offsets, slot lists and slots a query fetches (three stages).
constexpr std::size_t kSceneryPrefetchAhead[3] = {12, 6, 3};
/// Most cells (and slots a cell row) a query prefetches: a box over more is large, and its
/// cells are read in order anyway.
constexpr std::size_t kSceneryMostCellsPrefetched = 27;

// ---- Small frames (small_frame.h) ----

/// The cell grid of a small frame (small_frame.cpp): boxes are laid into a grid over the two
/// axes other than the sweep axis and each cell is swept alone, so a box meets only the
/// candidates of its own cells instead of every box whose interval it crosses on the sweep
/// axis. Cells per grid axis: at most sqrt(n / kSmallFrameBoxesPerCell) (a cell's fixed cost
/// amortised over enough boxes), at most 1 / (kSmallFrameCellsPerExtent × the mean extent
/// relative to the span) (few boxes copied into two cells), and at most
/// kSmallFrameMaxCellsPerAxis (a cell index in a byte). Measured on one thread (CPU time,
/// uniform scenes, d = 0.05 and 0.35, 2^12 to 2^16): 256 boxes a cell led 128 by 0-10 % from
/// 2^14 up and tied below, 512 and 1024 trailed at 2^12 to 2^14 by up to 20 %, 64 trailed
/// everywhere; the extent bound (1, 2 or 4 cells per mean extent) changed little, since on
/// these scenes the count bound is the tighter one.
constexpr double kSmallFrameBoxesPerCell = 256.0;
constexpr double kSmallFrameCellsPerExtent = 4.0;
constexpr uint32_t kSmallFrameMaxCellsPerAxis = 64;
/// The parallel cell sweep hands out runs of whole cells of at least kUnitBoxes / this many
/// entries (work_units.h), and at most kUnitsPerThread runs a thread: the cells' sweeps differ
/// in cost, so a thread whose runs came out dear is helped by the others.
constexpr std::size_t kSmallFrameSweepUnitsPerBoxUnit = 4;
/// Most threads on which Method::kAuto answers frames of every size with the small-frame
/// kernel (its cells in parallel) rather than the paper's parallel sweep (frame_plan.h).
/// Measured on the 2-core VM (uniform, d = 0.35, skin off, steady median, one run, other builds
/// running, load 19-21): at 2^17 the kernel on two threads took 214-423 ms against the
/// parallel sweep's 490-612 on two threads and 370-380 for the kernel on one; at 2^15 the
/// kernel on two threads 50 ms against 108 on one, at 2^13 1.17 against 1.11 (one unit of
/// boxes: nothing to share), so parallel_min_boxes (2^15) stays the cut-off below which a
/// frame runs on one thread. Above two threads the kernel (its key sort serial below 2^19
/// boxes) is unmeasured against the paper's sweep, which scales with cores (its §7): the sweep
/// keeps them.
constexpr int kKernelMostThreads = 2;

// ---- Box queries against the last frame (frame_query.h) ----

/// Query boxes a frame is scanned for before its index is built: building the static index of
/// a frame costs about as much as this many one-box scans of it (2^20 uniform boxes on the
/// loaded 2-core VM: an index 110-140 ms, a one-box scan 2.7 ms in a loop and 3.8-10 ms alone;
/// sap_bench -e query), so that rent-or-buy rule pays about twice the cheaper of the two.
constexpr std::size_t kQueryScansPerIndexBuild = 48;
/// Frame boxes a scan tests against every query box before moving on: their primary-axis
/// bounds (16 bytes a box) stay in the L2 cache while each query box reads them.
constexpr std::size_t kQueryScanBlock = 8192;
/// Fewest frame boxes worth a thread of their own in a scan.
constexpr std::size_t kMinScannedBoxesPerThread = 32768;

// ---- Large-world coordinates (sort keys relative to the frame) ----

/// The keys are float32 of (coordinate - origin). The origin is 0 (the keys of the
/// coordinates themselves) unless the frame's centre lies more than this many half-spans from
/// 0: there keys of the coordinates would be at least that many times coarser than keys
/// relative to the centre (UTM and ECEF coordinates, for example).
constexpr double kFarFromOriginInSpans = 64.0;
/// The origin of an axis is kept from frame to frame, so that the partition bounds B stay valid
/// (temporal coherence), until the frame's centre moved by more than this fraction of its span:
/// then precision near the boxes would start to suffer and the origin is re-centred.
constexpr double kOriginDriftInSpans = 0.125;

// ---- Box copies and the frame history ----

/// Boxes the history compares, then copies, together: a block of records read into the
/// thread's stack (6 bounds and an id a box, 28 KB) stays in L1/L2 while it is compared and
/// written, and a block with no change is never written.
constexpr std::size_t kHistoryBlockBoxes = 512;

// When buffers are given back after a burst of large frames: memory_policy.h.

// ---- Pair lists (pair_sort.h) ----

/// Pairs of one chunk of a pairing thread's list (8 bytes a pair, 64 KiB): large enough that
/// starting a chunk is rare, small enough that a thread with few pairs holds little.
constexpr std::size_t kPairChunkPairs = std::size_t{1} << 13;
/// Runs of pairs sharing `a` up to this long are insertion-sorted by b, longer ones by
/// std::sort.
constexpr std::size_t kPairInsertionSortLimit = 16;
/// Values of a one thread takes at a time when the runs are sorted in parallel: the runs are
/// short, so a chunk must hold many of them to be worth a scheduling step.
constexpr std::size_t kPairRunChunk = 4096;
/// Below this many pairs one thread merges the threads' parts: a team's barriers and the
/// second row of counts cost more (measured: 26k pairs of 2^17 boxes, 0.19 ms on one thread,
/// 0.30 on two).
constexpr std::size_t kParallelMergePairs = 65536;

// ---- Automatic skin (kept candidates, skin_list.h) ----

/// Skins tried, in multiples of the measured per-frame motion: a skin s lasts about
/// s / (2 v) frames at motion v. The cost model (frame_plan.cpp) picks the cheapest.
constexpr double kSkinInMotions[] = {2, 3, 4, 6, 8, 12, 16, 24, 32, 48, 64};
/// Largest skin, in mean box extents: beyond it the candidates grow faster than any cost
/// model of a uniform scene predicts in a clustered one (a guard, not a tuning).
constexpr double kMaxSkinInExtents = 2.0;
/// A skin is only used when the model expects it to cost at most this fraction of a plain
/// sweep per frame: a margin for the model's error, so that fast motion turns skin off.
constexpr double kSkinWorthIt = 0.8;
/// Skins whose expected cost is within this factor of the cheapest count as equally cheap;
/// the smallest of them is used (its candidates are the fewest, its prediction the surest).
constexpr double kSkinCostMargin = 1.1;
/// Frames whose largest displacement sets the motion v: the maximum over a short window,
/// since one box leaving its skin forces a new sweep.
constexpr int kMotionWindow = 4;
/// Smallest frame for which a skin is considered: below it a sweep costs microseconds.
constexpr std::size_t kMinSkinBoxes = 1024;
/// The measured check of the automatic skin (skin_audit.h): frames answered with a skin whose
/// mean cost is weighed against the plain frames', and the plain frames of the first probation
/// after the skin's frames cost more (each further failure doubles it, up to the longest). A
/// window spans a few cycles of kept candidates (about 17 frames each at 1 % motion).
constexpr int kSkinAuditFrames = 16;
constexpr int kSkinAuditFirstProbation = 32;
constexpr int kSkinAuditLongestProbation = 1024;
/// Until a pass has been measured: nanoseconds per kept candidate and per box (containment
/// check and gather) of a pass on one thread, conservative.
constexpr double kInitialNsPerCandidate = 10.0;
constexpr double kInitialNsPerBox = 5.0;
/// Until a grown sweep has been measured: nanoseconds per box to grow the boxes and per
/// candidate to keep the grown sweep's pairs (spatial order, rows), one thread, conservative.
constexpr double kInitialGrowNsPerBox = 10.0;
constexpr double kInitialKeepNsPerCandidate = 30.0;
/// Weight of the newest measurement in the running cost averages.
constexpr double kCostSmoothing = 0.5;
/// Boxes or candidates ahead a kept-candidate pass asks for the cache line it will need:
/// enough to cover a memory latency with the work of the ones in between.
constexpr std::size_t kSkinPrefetchAhead = 32;
/// Boxes a thread's gather handles between two checks that no box of its share has left its
/// skin (a box outside ends the pass early).
constexpr std::size_t kGatherBlockBoxes = 4096;

}  // namespace sap_broadphase::tuning
