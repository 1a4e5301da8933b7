// Single-axis sort-and-sweep for small frames (small_frame.h).
//
// Candidates are tested on float32 bounds rounded outward (sort_keys.h), measured from the
// frame's key origin (key_origin.h) as the sweep's keys are, so a float test never
// misses a true overlap; each float hit is confirmed, by floats far enough apart or else on the
// float64 input by boxesOverlap, so the result is exact. Floats halve the bytes a block reads and
// double the lanes of a vector.
#include "core/strategies/small_frame.h"

#include <algorithm>
#include <cmath>
#include <limits>
#include <type_traits>

#include "core/assert.h"
#include "core/runner/buffers.h"
#include "core/runner/work_units.h"
#include "core/sweep/key_origin.h"
#include "core/sweep/radix_sort.h"
#include "core/sweep/sort_keys.h"
#include "core/tuning.h"

#if defined(__x86_64__) || defined(__i386__)
#define SAP_SMALL_FRAME_AVX2 1
#include <immintrin.h>
#endif

namespace sap_broadphase {
namespace {

// Candidates one AVX2 block tests; also the NaN padding after the last box.
constexpr uint32_t kBlock = 8;

// Mean finite extent over the span of the finite bounds on inAxis; infinite when the span is
// degenerate (a sweep on that axis would see every box start at once).
double relativeExtent(FrameSpread& ioSpread, int inAxis) {
  const AxisSpread& spread = ioSpread.axis(inAxis, 1);
  const double span = spread.span();
  if (!(span > 0.0) || !std::isfinite(span)) return std::numeric_limits<double>::infinity();
  return spread.meanExtent() / span;
}

// The sweep-order float bounds of one run of candidates, the boxes of one grid cell; axis 0 is
// the sweep axis, each low array padded with kBlock NaNs.
struct SweepArrays {
  const float* lo[3];
  const float* hi[3];
  uint32_t count;
};

// The sweep in blocks of kBlock candidates: sorted lows make the first low past the end of
// box i the end of its candidates, and the NaN padding ends the last box's. The sweep-axis
// test low_i <= hi_j holds for every j > i (sorted lows, outward keys: lo_j <= hi_j), so only
// lo_j <= hi_i is tested on that axis. Each block's test is branch-free (bitwise, not
// short-circuit), so mispredictions stay with the rare hits and the compiler may vectorise the
// lanes with whatever the target has. inReport(i, j) receives each float hit.
template <typename Report>
void sweepPortable(const SweepArrays& inArrays, Report&& inReport) {
  const float *lo0 = inArrays.lo[0], *lo1 = inArrays.lo[1], *lo2 = inArrays.lo[2];
  const float *hi0 = inArrays.hi[0], *hi1 = inArrays.hi[1], *hi2 = inArrays.hi[2];
  for (uint32_t i = 0; i < inArrays.count; ++i) {
    const float high0 = hi0[i], low1 = lo1[i], high1 = hi1[i], low2 = lo2[i], high2 = hi2[i];
    for (uint32_t j = i + 1; lo0[j] <= high0; j += kBlock) {
      unsigned lanes = 0;
      for (uint32_t lane = 0; lane < kBlock; ++lane) {
        const uint32_t k = j + lane;
        const bool hit = (lo0[k] <= high0) & (lo1[k] <= high1) & (low1 <= hi1[k]) &
                         (lo2[k] <= high2) & (low2 <= hi2[k]);
        lanes |= unsigned{hit} << lane;
      }
      for (; lanes != 0; lanes &= lanes - 1) inReport(i, j + __builtin_ctz(lanes));
    }
  }
}

#if SAP_SMALL_FRAME_AVX2
// The same sweep with each block's five compares as AVX2 instructions; a block may extend past
// the last candidate, whose extra lanes fail the sweep-axis test (or meet NaN padding).
template <typename Report>
__attribute__((target("avx2"))) void sweepAvx2(const SweepArrays& inArrays, Report&& inReport) {
  const float *lo0 = inArrays.lo[0], *lo1 = inArrays.lo[1], *lo2 = inArrays.lo[2];
  const float *hi0 = inArrays.hi[0], *hi1 = inArrays.hi[1], *hi2 = inArrays.hi[2];
  for (uint32_t i = 0; i < inArrays.count; ++i) {
    const float end = hi0[i];
    const __m256 high0 = _mm256_set1_ps(end);
    const __m256 high1 = _mm256_set1_ps(hi1[i]), low1 = _mm256_set1_ps(lo1[i]);
    const __m256 high2 = _mm256_set1_ps(hi2[i]), low2 = _mm256_set1_ps(lo2[i]);
    for (uint32_t j = i + 1; lo0[j] <= end; j += kBlock) {
      __m256 hit = _mm256_cmp_ps(_mm256_loadu_ps(lo0 + j), high0, _CMP_LE_OQ);
      hit = _mm256_and_ps(hit, _mm256_cmp_ps(_mm256_loadu_ps(lo1 + j), high1, _CMP_LE_OQ));
      hit = _mm256_and_ps(hit, _mm256_cmp_ps(low1, _mm256_loadu_ps(hi1 + j), _CMP_LE_OQ));
      hit = _mm256_and_ps(hit, _mm256_cmp_ps(_mm256_loadu_ps(lo2 + j), high2, _CMP_LE_OQ));
      hit = _mm256_and_ps(hit, _mm256_cmp_ps(low2, _mm256_loadu_ps(hi2 + j), _CMP_LE_OQ));
      for (auto lanes = static_cast<unsigned>(_mm256_movemask_ps(hit)); lanes != 0;
           lanes &= lanes - 1)
        inReport(i, j + __builtin_ctz(lanes));
    }
  }
}
#endif

// True when an outward low inLow and an outward high inHigh prove low <= high for the exact
// values they bound: the exact low lies at most one float above inLow and the exact high at
// most one below inHigh, so a float strictly between the two settles it. Keys of adjacent
// floats differ by one, except across zero, where -0.0's missing key makes it two: three keys
// apart always leaves a float between.
inline bool provesOrder(float inLow, float inHigh) {
  return uint64_t{floatKeyFlat(inHigh)} >= uint64_t{floatKeyFlat(inLow)} + 3;
}

// True when the float bounds of entries i and j of a run prove the exact boxes overlap.
inline bool provesOverlap(const SweepArrays& inArrays, uint32_t i, uint32_t j) {
  bool proven = true;
  for (int slot = 0; slot < 3; ++slot) {
    proven &= provesOrder(inArrays.lo[slot][j], inArrays.hi[slot][i]) &
              provesOrder(inArrays.lo[slot][i], inArrays.hi[slot][j]);
  }
  return proven;
}

// Reports a float hit between entries i and j of a run (boxes inFirst and inSecond) when the
// exact boxes overlap: proven by the floats (most hits: no float64 bounds of two random boxes
// fetched), else tested on the float64 input.
inline void reportIfExact(const BoxColumns& inBoxes, const SweepArrays& inArrays, uint32_t i,
                          uint32_t j, uint32_t inFirst, uint32_t inSecond, PairChunks& outPairs) {
  if ((provesOverlap(inArrays, i, j) || boxesOverlap(inBoxes, inFirst, inSecond)) &&
      filtersAllow(inBoxes, inFirst, inSecond))
    outPairs.push_back(makeIdPair(inBoxes.ids[inFirst], inBoxes.ids[inSecond]));
}

bool cpuHasAvx2() {
#if SAP_SMALL_FRAME_AVX2
  static const bool has_avx2 = __builtin_cpu_supports("avx2");
  return has_avx2;
#else
  return false;
#endif
}

template <typename Report>
void sweepWith(bool inAvx2, const SweepArrays& inArrays, Report&& inReport) {
#if SAP_SMALL_FRAME_AVX2
  if (inAvx2) return sweepAvx2(inArrays, inReport);
#endif
  (void)inAvx2;
  sweepPortable(inArrays, inReport);
}

// One axis of the cell grid laid over the two axes other than the sweep axis: equal cells
// over the span of the finite bounds. A value's cell is monotone in the value (clamped at both
// ends, so infinite bounds fall in the first or last cell), so two intervals that overlap both
// contain the larger of their lows, and both reach its cell.
struct GridAxis {
  float base = 0.0f;
  float scale = 0.0f;  ///< cells per unit
  uint32_t cells = 1;

  uint32_t of(float inValue) const {
    if (cells == 1) return 0;
    const float position = (inValue - base) * scale;
    const float last = static_cast<float>(cells - 1);
    return static_cast<uint32_t>(position > 0.0f ? std::min(position, last) : 0.0f);
  }
};

// The cells of the grid on inAxis: as many as keep about kSmallFrameBoxesPerCell boxes in a
// cell of an even scene, and no more than keep a cell kSmallFrameCellsPerExtent times wider
// than the mean box (a box then spans one cell, rarely two, so few are copied into two).
GridAxis gridAxis(FrameSpread& ioSpread, const KeyOrigin& inOrigin, int inAxis,
                  std::size_t inBoxes) {
  GridAxis grid;
  const AxisSpread& spread = ioSpread.axis(inAxis, 1);
  const double span = spread.span();
  const double relative = relativeExtent(ioSpread, inAxis);
  const double by_count = std::sqrt(static_cast<double>(inBoxes) / tuning::kSmallFrameBoxesPerCell);
  const double by_extent = 1.0 / (tuning::kSmallFrameCellsPerExtent * relative);
  const double cells = std::min({by_count, by_extent, double{tuning::kSmallFrameMaxCellsPerAxis}});
  if (!(cells >= 2.0) || !std::isfinite(span)) return grid;
  grid.cells = static_cast<uint32_t>(cells);
  grid.base = static_cast<float>(spread.lowest - inOrigin.origin[inAxis]);
  grid.scale = static_cast<float>(grid.cells / span);
  if (!(grid.scale > 0.0f) || !std::isfinite(grid.scale)) grid = GridAxis();
  return grid;
}

template <typename Visit>
void forEachCell(uint32_t inRange, uint32_t inCells1, Visit&& inVisit) {
  for (uint32_t a = inRange & 0xFF; a <= ((inRange >> 8) & 0xFF); ++a)
    for (uint32_t b = (inRange >> 16) & 0xFF; b <= inRange >> 24; ++b) inVisit(a * inCells1 + b);
}

// Each box's outward float bounds relative to the key origin, six in a row: low and high on
// inAxes[0] (the sweep axis), then on inAxes[1] and inAxes[2]. Keys are measured from the
// frame's key origin, as the sweep's are: a robot's few thousand boxes in UTM or Earth-centred
// coordinates would otherwise share their float32 values and all become candidates of one
// another.
void outwardBoundsPortable(const BoxColumns& inBoxes, const KeyOrigin& inOrigin,
                           const int (&inAxes)[3], uint32_t inFirst, uint32_t inEnd,
                           float* outBounds) {
  for (uint32_t i = inFirst; i < inEnd; ++i) {
    float* bounds = outBounds + 6 * std::size_t{i};
    for (int slot = 0; slot < 3; ++slot) {
      const int axis = inAxes[slot];
      bounds[2 * slot] = keyToFloat(inOrigin.low(axis, inBoxes.lo[axis][i]));
      bounds[2 * slot + 1] = keyToFloat(inOrigin.high(axis, inBoxes.hi[axis][i]));
    }
  }
}

#if SAP_SMALL_FRAME_AVX2
// KeyOrigin::low (inLow) or high of four values at once, as floats: inValues - inOrigin as a
// double and its rounding error (TwoSum), rounded to the nearest float, then one float down
// (up) where that float lies above (below) the exact difference. One float down from +-0 is
// the least negative denormal; from +inf (a finite difference beyond the floats) the largest
// float.
__attribute__((target("avx2"))) __m128 outwardFloats(__m256d inValues, __m256d inOrigin,
                                                     bool inLow) {
  const __m256d zero = _mm256_setzero_pd();
  const __m256d difference = _mm256_sub_pd(inValues, inOrigin);
  const __m256d back = _mm256_sub_pd(difference, inValues);
  const __m256d error = _mm256_add_pd(_mm256_sub_pd(inValues, _mm256_sub_pd(difference, back)),
                                      _mm256_sub_pd(_mm256_sub_pd(zero, inOrigin), back));
  const __m128 nearest = _mm256_cvtpd_ps(difference);
  const __m256d widened = _mm256_cvtps_pd(nearest);
  const __m256d same = _mm256_cmp_pd(widened, difference, _CMP_EQ_OQ);
  const __m256d wrong =
      inLow ? _mm256_or_pd(_mm256_cmp_pd(widened, difference, _CMP_GT_OQ),
                           _mm256_and_pd(same, _mm256_cmp_pd(error, zero, _CMP_LT_OQ)))
            : _mm256_or_pd(_mm256_cmp_pd(widened, difference, _CMP_LT_OQ),
                           _mm256_and_pd(same, _mm256_cmp_pd(error, zero, _CMP_GT_OQ)));
  const __m128i step_lanes = _mm256_castsi256_si128(_mm256_permutevar8x32_epi32(
      _mm256_castpd_si256(wrong), _mm256_setr_epi32(0, 2, 4, 6, 0, 0, 0, 0)));
  const __m128i bits = _mm_castps_si128(nearest);
  const __m128i toward_larger = _mm_or_si128(_mm_srai_epi32(bits, 31), _mm_set1_epi32(1));
  const __m128i delta = inLow ? _mm_sub_epi32(_mm_setzero_si128(), toward_larger) : toward_larger;
  const __m128i is_zero =
      _mm_cmpeq_epi32(_mm_and_si128(bits, _mm_set1_epi32(0x7FFFFFFF)), _mm_setzero_si128());
  const __m128i from_zero = _mm_set1_epi32(inLow ? static_cast<int>(0x80000001u) : 1);
  const __m128i stepped = _mm_blendv_epi8(_mm_add_epi32(bits, delta), from_zero, is_zero);
  return _mm_castsi128_ps(_mm_blendv_epi8(bits, stepped, step_lanes));
}

// outwardBoundsPortable, four boxes at a time; the last few boxes on the portable loop.
__attribute__((target("avx2"))) void outwardBoundsAvx2(const BoxColumns& inBoxes,
                                                       const KeyOrigin& inOrigin,
                                                       const int (&inAxes)[3], uint32_t inFirst,
                                                       uint32_t inEnd, float* outBounds) {
  uint32_t i = inFirst;
  for (; i + 4 <= inEnd; i += 4) {
    alignas(16) float lanes[6][4];
    for (int slot = 0; slot < 3; ++slot) {
      const int axis = inAxes[slot];
      const __m256d origin = _mm256_set1_pd(inOrigin.origin[axis]);
      _mm_store_ps(lanes[2 * slot],
                   outwardFloats(_mm256_loadu_pd(inBoxes.lo[axis].data() + i), origin, true));
      _mm_store_ps(lanes[2 * slot + 1],
                   outwardFloats(_mm256_loadu_pd(inBoxes.hi[axis].data() + i), origin, false));
    }
    for (uint32_t box = 0; box < 4; ++box)
      for (int bound = 0; bound < 6; ++bound)
        outBounds[6 * std::size_t{i + box} + bound] = lanes[bound][box];
  }
  outwardBoundsPortable(inBoxes, inOrigin, inAxes, i, inEnd, outBounds);
}
#endif

// One pass over the boxes in input order, a unit of boxes at a time on the frame's threads:
// their outward float bounds (six in a row, inAxis first), the sort key of each low on inAxis
// and the cells each box reaches (packed as four bytes: first and last cell on grid axis 0,
// then on grid axis 1).
void measureBoxes(const BoxColumns& inBoxes, const KeyOrigin& inOrigin, int inAxis,
                  const GridAxis (&inGrid)[2], bool inAvx2, SmallFrameWorkspace& ioWork) {
  const auto n = static_cast<uint32_t>(inBoxes.size());
  resizeDiscarding(ioWork.order, n);
  resizeDiscarding(ioWork.scratch, n);
  resizeDiscarding(ioWork.bounds, 6 * std::size_t{n});
  resizeDiscarding(ioWork.cell_range, n);
  const int axes[3] = {inAxis, (inAxis + 1) % 3, (inAxis + 2) % 3};
  runOverItems(WorkUnits{n}, [&](std::size_t inBegin, std::size_t inEnd) {
    const auto first = static_cast<uint32_t>(inBegin), end = static_cast<uint32_t>(inEnd);
#if SAP_SMALL_FRAME_AVX2
    if (inAvx2)
      outwardBoundsAvx2(inBoxes, inOrigin, axes, first, end, ioWork.bounds.data());
    else
#endif
      outwardBoundsPortable(inBoxes, inOrigin, axes, first, end, ioWork.bounds.data());
    for (uint32_t i = first; i < end; ++i) {
      const float* bounds = ioWork.bounds.data() + 6 * std::size_t{i};
      ioWork.order[i] = packKeyIndex(floatKeyFlat(bounds[0]), i);
      ioWork.cell_range[i] = inGrid[0].of(bounds[2]) | inGrid[0].of(bounds[3]) << 8 |
                             inGrid[1].of(bounds[4]) << 16 | inGrid[1].of(bounds[5]) << 24;
    }
  });
  (void)inAvx2;
}

// Cells a unit of the passes over the cells' prefix handles: a few thousand cells at most, so
// a pass has a few units.
constexpr std::size_t kCellsPerUnit = 256;

// Where each unit of the sorted boxes writes into each cell: every unit counts the entries it
// adds to each cell (its row of unit_cell_count), then, cell by cell and unit by unit in
// order, the counts become the units' first entries (the same layout as one pass over the
// boxes in sorted order would give, whatever the thread count), and cell_start each cell's run
// (its entries and kBlock of padding). Only the prefix over the cells' totals is serial.
void placeUnitsInCells(const uint64_t* inSorted, const WorkUnits& inUnits, uint32_t inCells,
                       uint32_t inCells1, SmallFrameWorkspace& ioWork) {
  Buffer<uint32_t>& counts = ioWork.unit_cell_count;
  resizeDiscarding(counts, inUnits.count() * inCells);
  runUnits(inUnits.count(), [&](std::size_t inUnit) {
    uint32_t* row = counts.data() + inUnit * inCells;
    std::fill(row, row + inCells, 0u);
    for (std::size_t k = inUnits.begin(inUnit); k < inUnits.end(inUnit); ++k)
      forEachCell(ioWork.cell_range[static_cast<uint32_t>(inSorted[k])], inCells1,
                  [&](uint32_t cell) { ++row[cell]; });
  });
  Buffer<uint32_t>& cell_start = ioWork.cell_start;
  resizeDiscarding(cell_start, std::size_t{inCells} + 1);
  const WorkUnits cell_units{inCells, kCellsPerUnit};
  // Each cell's run length, in cell_start[cell + 1] until the prefix below.
  runOverItems(cell_units, [&](std::size_t inBegin, std::size_t inEnd) {
    for (std::size_t cell = inBegin; cell < inEnd; ++cell) {
      uint32_t entries = kBlock;
      for (std::size_t unit = 0; unit < inUnits.count(); ++unit)
        entries += counts[unit * inCells + cell];
      cell_start[cell + 1] = entries;
    }
  });
  cell_start[0] = 0;
  for (uint32_t cell = 0; cell < inCells; ++cell) cell_start[cell + 1] += cell_start[cell];
  runOverItems(cell_units, [&](std::size_t inBegin, std::size_t inEnd) {
    for (std::size_t cell = inBegin; cell < inEnd; ++cell) {
      uint32_t next = cell_start[cell];
      for (std::size_t unit = 0; unit < inUnits.count(); ++unit) {
        uint32_t& count = counts[unit * inCells + cell];
        const uint32_t entries = count;
        count = next;  // from now on the unit's next entry in the cell
        next += entries;
      }
      SAP_ASSERT(next + kBlock == cell_start[cell + 1], "a cell's entries and padding disagree");
    }
  });
}

// Sorts the boxes by low key on the sweep axis and lists each, in that order, in every cell it
// reaches (box_of): each cell's run is sorted by low key, its bounds copied in by gatherCell.
// The sort and the listing run on the frame's threads, the listing a unit of the sorted boxes
// at a time, each unit into the entries placeUnitsInCells gave it.
void fillCells(const BoxColumns& inBoxes, const KeyOrigin& inOrigin, int inAxis,
               const GridAxis (&inGrid)[2], bool inAvx2, SmallFrameWorkspace& ioWork) {
  const auto n = static_cast<uint32_t>(inBoxes.size());
  measureBoxes(inBoxes, inOrigin, inAxis, inGrid, inAvx2, ioWork);
  const uint64_t* sorted = radixSortPacked(ioWork.order.data(), ioWork.scratch.data(), n);
  const uint32_t cells = inGrid[0].cells * inGrid[1].cells;
  const WorkUnits units{n};
  placeUnitsInCells(sorted, units, cells, inGrid[1].cells, ioWork);
  const uint32_t entries = ioWork.cell_start[cells];
  for (int slot = 0; slot < 3; ++slot) {
    resizeDiscarding(ioWork.lo[slot], entries);
    resizeDiscarding(ioWork.hi[slot], entries);
  }
  resizeDiscarding(ioWork.box_of, entries);
  runUnits(units.count(), [&](std::size_t inUnit) {
    uint32_t* cursor = ioWork.unit_cell_count.data() + inUnit * cells;
    for (std::size_t k = units.begin(inUnit); k < units.end(inUnit); ++k) {
      const auto box = static_cast<uint32_t>(sorted[k]);
      forEachCell(ioWork.cell_range[box], inGrid[1].cells,
                  [&](uint32_t cell) { ioWork.box_of[cursor[cell]++] = box; });
    }
  });
}

// Copies the bounds of the boxes of one cell's run into the run's arrays, and its padding: a
// run is written in order, by the one worker that then sweeps it (while it is in its cache),
// rather than a few entries at a time by every unit of boxes, whose writes would share cache
// lines with other units' (a cell's share of a unit is a few entries).
void gatherCell(uint32_t inCell, SmallFrameWorkspace& ioWork) {
  const uint32_t first = ioWork.cell_start[inCell];
  const uint32_t padding = ioWork.cell_start[inCell + 1] - kBlock;
  const float* bounds = ioWork.bounds.data();
  for (uint32_t entry = first; entry < padding; ++entry) {
    const float* box_bounds = bounds + 6 * std::size_t{ioWork.box_of[entry]};
    for (int slot = 0; slot < 3; ++slot) {
      ioWork.lo[slot][entry] = box_bounds[2 * slot];
      ioWork.hi[slot][entry] = box_bounds[2 * slot + 1];
    }
  }
  const float nan = std::numeric_limits<float>::quiet_NaN();
  for (uint32_t entry = padding; entry < padding + kBlock; ++entry) {
    for (int slot = 0; slot < 3; ++slot) ioWork.lo[slot][entry] = ioWork.hi[slot][entry] = nan;
    ioWork.box_of[entry] = 0;
  }
}

// Cuts the cells into runs of consecutive cells of about inEntries entries each (a cell is
// never split): the units of the parallel sweep. outFirstCell holds each unit's first cell,
// then the cell count.
void cutCellsIntoUnits(const Buffer<uint32_t>& inCellStart, uint32_t inEntries,
                       std::vector<uint32_t>& outFirstCell) {
  const auto cells = static_cast<uint32_t>(inCellStart.size() - 1);
  outFirstCell.assign(1, 0);
  for (uint32_t cell = 1; cell < cells; ++cell)
    if (inCellStart[cell] - inCellStart[outFirstCell.back()] >= inEntries)
      outFirstCell.push_back(cell);
  outFirstCell.push_back(cells);
}

// Sweeps one cell of the grid; a float hit is reported only in the cell of the larger lows
// (the one cell both boxes reach that is a function of the pair alone), so a pair whose boxes
// share several cells is reported once. Without a grid, the one cell holds every box.
void sweepCell(const BoxColumns& inBoxes, const GridAxis (&inGrid)[2], bool inAvx2,
               const SmallFrameWorkspace& inWork, uint32_t inCell, PairChunks& outPairs) {
  const uint32_t cells1 = inGrid[1].cells;
  const uint32_t first = inWork.cell_start[inCell];
  SweepArrays arrays;
  for (int slot = 0; slot < 3; ++slot) {
    arrays.lo[slot] = inWork.lo[slot].data() + first;
    arrays.hi[slot] = inWork.hi[slot].data() + first;
  }
  arrays.count = inWork.cell_start[inCell + 1] - first - kBlock;
  const uint32_t* box = inWork.box_of.data() + first;
  sweepWith(inAvx2, arrays, [&](uint32_t i, uint32_t j) {
    const uint32_t owner = inGrid[0].of(std::max(arrays.lo[1][i], arrays.lo[1][j])) * cells1 +
                           inGrid[1].of(std::max(arrays.lo[2][i], arrays.lo[2][j]));
    if (owner == inCell) reportIfExact(inBoxes, arrays, i, j, box[i], box[j], outPairs);
  });
}

// Gathers and sweeps every cell, runs of cells (units) on the frame's threads, each worker into
// its own list; the lists are merged into canonical order.
void sweepCells(const BoxColumns& inBoxes, const GridAxis (&inGrid)[2], bool inAvx2,
                SmallFrameWorkspace& ioWork, PairList& outPairs) {
  const uint32_t entries = ioWork.cell_start.back();
  const int threads = passThreads();
  const auto unit_entries = static_cast<uint32_t>(
      threads <= 1 ? entries
                   : std::max<std::size_t>(kUnitBoxes / tuning::kSmallFrameSweepUnitsPerBoxUnit,
                                           entries / (kUnitsPerThread * threads)));
  cutCellsIntoUnits(ioWork.cell_start, unit_entries, ioWork.unit_first_cell);
  const std::vector<uint32_t>& first_cell = ioWork.unit_first_cell;
  const std::size_t units = first_cell.size() - 1;
  const int team = teamForUnits(units, threads);
  ioWork.pairs_per_worker.resize(std::max<std::size_t>(1, team));
  PairBudget budget(ioWork.max_pairs);
  for (PairChunks& pairs : ioWork.pairs_per_worker) {
    pairs.clear();
    pairs.setBudget(&budget);
  }
  const BudgetScope budget_scope(ioWork.pairs_per_worker);
  runUnitsOnWorkers(units, [&](std::size_t inUnit, int inWorker) {
    SAP_ASSERT(inWorker < team, "a worker beyond the sweep's lists");
    if (budget.exhausted()) return;  // the frame is refused: the units left need not run
    for (uint32_t cell = first_cell[inUnit]; cell < first_cell[inUnit + 1]; ++cell) {
      gatherCell(cell, ioWork);
      sweepCell(inBoxes, inGrid, inAvx2, ioWork, cell, ioWork.pairs_per_worker[inWorker]);
    }
  });
  sortPairsCanonical(ioWork.pairs_per_worker, outPairs, ioWork.pair_scratch);
}

void pairWith(const BoxColumns& inBoxes, FrameSpread& ioSpread, SmallFrameWorkspace& ioWork,
              PairList& outPairs, bool inAvx2) {
  outPairs.clear();
  if (inBoxes.size() < 2) return;
  SAP_ASSERT(&ioSpread.boxes() == &inBoxes, "the small frame reads the spread of other boxes");
  const auto n = static_cast<uint32_t>(inBoxes.size());
  for (int axis = 0; axis < 3; ++axis) ioSpread.axis(axis);  // measured once, here
  const int axis = chooseSmallFrameAxis(ioSpread);
  const KeyOrigin origin = keyOriginOf(ioSpread);
  const GridAxis grid[2] = {gridAxis(ioSpread, origin, (axis + 1) % 3, n),
                            gridAxis(ioSpread, origin, (axis + 2) % 3, n)};
  ioWork.grid_cells = grid[0].cells * grid[1].cells;
  fillCells(inBoxes, origin, axis, grid, inAvx2, ioWork);
  sweepCells(inBoxes, grid, inAvx2, ioWork, outPairs);
}

}  // namespace

std::size_t SmallFrameWorkspace::bytesHeld() const {
  const auto bytesOf = [](const auto& inVector) {
    return inVector.capacity() * sizeof(typename std::decay_t<decltype(inVector)>::value_type);
  };
  std::size_t bytes = bytesOf(order) + bytesOf(scratch) + bytesOf(bounds) + bytesOf(box_of) +
                      bytesOf(cell_start) + bytesOf(cell_range) + bytesOf(unit_cell_count) +
                      bytesOf(unit_first_cell) + bytesOf(pairs_per_worker) +
                      bytesOf(pair_scratch.pairs) + bytesOf(pair_scratch.offsets);
  for (int axis = 0; axis < 3; ++axis) bytes += bytesOf(lo[axis]) + bytesOf(hi[axis]);
  for (const PairChunks& pairs : pairs_per_worker) bytes += pairs.bytesHeld();
  return bytes;
}

int chooseSmallFrameAxis(FrameSpread& ioSpread) {
  int best_axis = 0;
  double best = relativeExtent(ioSpread, 0);
  for (int axis = 1; axis < 3; ++axis) {
    const double relative = relativeExtent(ioSpread, axis);
    if (relative < best) {
      best = relative;
      best_axis = axis;
    }
  }
  return best_axis;
}

void pairSmallFrame(const BoxColumns& inBoxes, FrameSpread& ioSpread, SmallFrameWorkspace& ioWork,
                    PairList& outPairs) {
  pairWith(inBoxes, ioSpread, ioWork, outPairs, cpuHasAvx2());
}

void pairSmallFrame(const BoxColumns& inBoxes, SmallFrameWorkspace& ioWork, PairList& outPairs) {
  FrameSpread spread(inBoxes);
  pairSmallFrame(inBoxes, spread, ioWork, outPairs);
}

void pairSmallFramePortable(const BoxColumns& inBoxes, SmallFrameWorkspace& ioWork,
                            PairList& outPairs) {
  FrameSpread spread(inBoxes);
  pairWith(inBoxes, spread, ioWork, outPairs, false);
}

}  // namespace sap_broadphase
