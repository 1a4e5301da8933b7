// The small-frame path: one thread, no state kept between frames.
//
// Below a few thousand boxes the bi-dimensional sweep's fixed costs (two endpoint sorts, the
// candidate ranges of Algorithm 1, SuccTrees sized to n) outweigh what it saves. A plain
// sort-and-sweep then wins: sort the boxes by low end on the sweep axis, lay them into the
// cells of a grid over the two other axes, and test each box against the boxes of its cells
// that start before it ends, several candidates at a time.
#pragma once

#include <cstddef>
#include <cstdint>
#include <vector>

#include "core/axis_spread.h"
#include "core/buffers.h"
#include "sap_broadphase/core/box_set.h"
#include "sap_broadphase/core/pair_set.h"

namespace sap_broadphase {

/// Largest frame worth handing to pairSmallFrame instead of the one-thread engine. Measured
/// with sap_microbench's BM_SmallFrame (uniform scenes, CPU time of one thread): the small
/// frame stays ahead up to 2^15 boxes at density 0.35 and beyond 2^16 at 0.05 (at 2^14: 3.3
/// against 5.3 ms, and 1.6 against 3.9 ms). Its candidates grow as n^(5/3) on a uniform scene,
/// the engine's as n, hence a crossover; 2^14 keeps a margin for denser scenes.
constexpr std::size_t kSmallFrameMaxBoxesOneThread = std::size_t{1} << 14;
/// The same against the parallel engine on two threads. Measured with `sap_bench -e skips`
/// (uniform, density 0.2, every frame swept, 2 cores idle): the small frame leads 2.04× at
/// 2^13, 1.53× at 2^14 and 1.15× at 2^15 and trails from 2^16 (1.07 / 2.19, 2.66 / 4.07,
/// 6.99 / 8.04, 20.0 / 15.4 ms); 2^14 keeps the margin for denser scenes.
constexpr std::size_t kSmallFrameMaxBoxesParallel = std::size_t{1} << 14;

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

/// Buffers of pairSmallFrame, reused from frame to frame (grown, never shrunk; growth does not
/// zero them).
struct SmallFrameWorkspace {
  Buffer<uint64_t> order;    ///< (low key << 32 | box) on the sweep axis, then sorted
  Buffer<uint64_t> scratch;  ///< the radix sort's second buffer
  /// Float32 bounds rounded outward (sort_keys.h) relative to the frame's key origin
  /// (key_origin.h), six per box in input order: low and high on the sweep axis, then on the
  /// two grid axes.
  Buffer<float> bounds;
  /// The grid's cells one after the other, each a run of its boxes sorted by low key on the
  /// sweep axis (a box reaching several cells is in each), structure of arrays of the bounds
  /// with axis 0 the sweep axis. Each run is followed by kBlock NaNs, so a block of candidates
  /// may read past its last box: NaN compares false, so padding never overlaps anything.
  Buffer<float> lo[3];
  Buffer<float> hi[3];
  Buffer<uint32_t> box_of;       ///< box index of each entry of a run
  Buffer<uint32_t> cell_start;   ///< first entry of each cell's run, then the total
  Buffer<uint32_t> cell_cursor;  ///< next free entry of each cell while filling
  Buffer<uint32_t> cell_range;   ///< the cells each box reaches (packed, input order)
  PairSortScratch pair_scratch;
  uint32_t grid_cells = 1;  ///< cells of the last frame's grid (1: one sweep of all boxes)
};

/// The sweep axis of a small frame: the one whose mean box extent is smallest relative to the
/// span of the finite bounds, i.e. the fewest boxes start inside a box's interval (read from
/// ioSpread, the spread of the frame's boxes, measured on one thread if not yet).
int chooseSmallFrameAxis(FrameSpread& ioSpread);

/// Every overlapping, filter-allowed pair of inBoxes (exactly bruteForcePairs' result), in
/// canonical order, into outPairs (replaced). One thread; AVX2 blocks of 8 candidates where
/// the CPU has them, a portable loop otherwise (chosen at run time). ioSpread is the spread of
/// inBoxes: the sweep axis and the key origin are read from it.
void pairSmallFrame(const BoxSet& inBoxes, FrameSpread& ioSpread, SmallFrameWorkspace& ioWork,
                    PairList& outPairs);
/// The same, measuring the spread of inBoxes itself.
void pairSmallFrame(const BoxSet& inBoxes, SmallFrameWorkspace& ioWork, PairList& outPairs);

/// The same, forced onto the portable loop (for tests and benchmarks on AVX2 machines).
void pairSmallFramePortable(const BoxSet& inBoxes, SmallFrameWorkspace& ioWork, PairList& outPairs);

/// True when pairSmallFrame uses the AVX2 blocks on this CPU.
bool smallFrameUsesAvx2();

}  // namespace sap_broadphase
