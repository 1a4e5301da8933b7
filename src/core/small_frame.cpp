// Single-axis sort-and-sweep for small frames (small_frame.h).
//
// Candidates are tested on float32 bounds rounded outward (sort_keys.h), measured from the
// frame's key origin (key_origin.h) as the sweep's keys are, so a float test never
// misses a true overlap; each float hit is confirmed on the float64 input by boxesOverlap, so
// the result is exact. Floats halve the bytes a block reads and double the lanes of a vector.
#include "core/small_frame.h"

#include <cmath>
#include <limits>

#include "core/assert.h"
#include "core/buffers.h"
#include "core/key_origin.h"
#include "core/radix_sort.h"
#include "core/sort_keys.h"

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

// Sorts the boxes by low key on inAxis and lays their outward float bounds out in sweep
// order, inAxis first. Keys are measured from the frame's key origin, as the sweep's are: a
// robot's few thousand boxes in UTM or Earth-centred coordinates would otherwise share their
// float32 values and all become candidates of one another.
void prepareSweep(const BoxSet& inBoxes, FrameSpread& ioSpread, int inAxis,
                  SmallFrameWorkspace& ioWork) {
  const auto n = static_cast<uint32_t>(inBoxes.size());
  const KeyOrigin origin = keyOriginOf(ioSpread, 1);
  resizeDiscarding(ioWork.order, n);
  resizeDiscarding(ioWork.scratch, n);
  const double* sweep_low = inBoxes.lo[inAxis].data();
  for (uint32_t i = 0; i < n; ++i)
    ioWork.order[i] = packKeyIndex(origin.low(inAxis, sweep_low[i]), i);
  const uint64_t* sorted = radixSortPacked(ioWork.order.data(), ioWork.scratch.data(), n);
  resizeDiscarding(ioWork.box_of, n);
  for (uint32_t k = 0; k < n; ++k) ioWork.box_of[k] = static_cast<uint32_t>(sorted[k]);
  const float nan = std::numeric_limits<float>::quiet_NaN();
  for (int slot = 0; slot < 3; ++slot) {
    const int axis = (inAxis + slot) % 3;
    const double* low = inBoxes.lo[axis].data();
    const double* high = inBoxes.hi[axis].data();
    std::vector<float>& sorted_low = ioWork.lo[slot];
    std::vector<float>& sorted_high = ioWork.hi[slot];
    resizeDiscarding(sorted_low, n + kBlock);
    resizeDiscarding(sorted_high, n + kBlock);
    for (uint32_t k = 0; k < n; ++k) {
      const uint32_t box = ioWork.box_of[k];
      sorted_low[k] = keyToFloat(origin.low(axis, low[box]));
      sorted_high[k] = keyToFloat(origin.high(axis, high[box]));
    }
    std::fill(sorted_low.begin() + n, sorted_low.end(), nan);
    std::fill(sorted_high.begin() + n, sorted_high.end(), nan);
  }
}

// Confirms a float hit between sweep positions inFirst and inSecond on the float64 input.
inline void reportIfExact(const BoxSet& inBoxes, const uint32_t* inBoxOf, uint32_t inFirst,
                          uint32_t inSecond, PairList& outPairs) {
  const uint32_t a = inBoxOf[inFirst];
  const uint32_t b = inBoxOf[inSecond];
  if (boxesOverlap(inBoxes, a, b) && filtersAllow(inBoxes, a, b))
    outPairs.push_back(makeIdPair(inBoxes.ids[a], inBoxes.ids[b]));
}

// The sweep in blocks of kBlock candidates: sorted lows make the first low past the end of
// box i the end of its candidates, and the NaN padding ends the last box's. Each block's test
// is branch-free (bitwise, not short-circuit), so mispredictions stay with the rare hits and
// the compiler may vectorise the lanes with whatever the target has.
void sweepPortable(const BoxSet& inBoxes, const SmallFrameWorkspace& inWork, PairList& outPairs) {
  const auto n = static_cast<uint32_t>(inBoxes.size());
  const float* lo0 = inWork.lo[0].data();
  const float* hi0 = inWork.hi[0].data();
  const float* lo1 = inWork.lo[1].data();
  const float* hi1 = inWork.hi[1].data();
  const float* lo2 = inWork.lo[2].data();
  const float* hi2 = inWork.hi[2].data();
  for (uint32_t i = 0; i < n; ++i) {
    const float low0 = lo0[i], high0 = hi0[i], low1 = lo1[i], high1 = hi1[i];
    const float low2 = lo2[i], high2 = hi2[i];
    for (uint32_t j = i + 1; lo0[j] <= high0; j += kBlock) {
      unsigned lanes = 0;
      for (uint32_t lane = 0; lane < kBlock; ++lane) {
        const uint32_t k = j + lane;
        const bool hit = (lo0[k] <= high0) & (low0 <= hi0[k]) & (lo1[k] <= high1) &
                         (low1 <= hi1[k]) & (lo2[k] <= high2) & (low2 <= hi2[k]);
        lanes |= unsigned{hit} << lane;
      }
      for (; lanes != 0; lanes &= lanes - 1)
        reportIfExact(inBoxes, inWork.box_of.data(), i, j + __builtin_ctz(lanes), outPairs);
    }
  }
}

#if SAP_SMALL_FRAME_AVX2
// The same sweep with each block's six compares as AVX2 instructions; a block may extend past
// the last candidate, whose extra lanes fail the sweep-axis test (or meet NaN padding).
__attribute__((target("avx2"))) void sweepAvx2(const BoxSet& inBoxes,
                                               const SmallFrameWorkspace& inWork,
                                               PairList& outPairs) {
  const auto n = static_cast<uint32_t>(inBoxes.size());
  const float* lo0 = inWork.lo[0].data();
  const float* hi0 = inWork.hi[0].data();
  const float* lo1 = inWork.lo[1].data();
  const float* hi1 = inWork.hi[1].data();
  const float* lo2 = inWork.lo[2].data();
  const float* hi2 = inWork.hi[2].data();
  for (uint32_t i = 0; i < n; ++i) {
    const float end = hi0[i];
    const __m256 high0 = _mm256_set1_ps(end), low0 = _mm256_set1_ps(lo0[i]);
    const __m256 high1 = _mm256_set1_ps(hi1[i]), low1 = _mm256_set1_ps(lo1[i]);
    const __m256 high2 = _mm256_set1_ps(hi2[i]), low2 = _mm256_set1_ps(lo2[i]);
    for (uint32_t j = i + 1; lo0[j] <= end; j += kBlock) {
      __m256 hit = _mm256_and_ps(_mm256_cmp_ps(_mm256_loadu_ps(lo0 + j), high0, _CMP_LE_OQ),
                                 _mm256_cmp_ps(low0, _mm256_loadu_ps(hi0 + j), _CMP_LE_OQ));
      hit = _mm256_and_ps(hit, _mm256_cmp_ps(_mm256_loadu_ps(lo1 + j), high1, _CMP_LE_OQ));
      hit = _mm256_and_ps(hit, _mm256_cmp_ps(low1, _mm256_loadu_ps(hi1 + j), _CMP_LE_OQ));
      hit = _mm256_and_ps(hit, _mm256_cmp_ps(_mm256_loadu_ps(lo2 + j), high2, _CMP_LE_OQ));
      hit = _mm256_and_ps(hit, _mm256_cmp_ps(low2, _mm256_loadu_ps(hi2 + j), _CMP_LE_OQ));
      for (auto lanes = static_cast<unsigned>(_mm256_movemask_ps(hit)); lanes != 0;
           lanes &= lanes - 1)
        reportIfExact(inBoxes, inWork.box_of.data(), i, j + __builtin_ctz(lanes), outPairs);
    }
  }
}

#endif

bool cpuHasAvx2() {
#if SAP_SMALL_FRAME_AVX2
  static const bool has_avx2 = __builtin_cpu_supports("avx2");
  return has_avx2;
#else
  return false;
#endif
}

template <typename Sweep>
void pairWith(const BoxSet& inBoxes, FrameSpread& ioSpread, SmallFrameWorkspace& ioWork,
              PairList& outPairs, Sweep&& inSweep) {
  outPairs.clear();
  if (inBoxes.size() < 2) return;
  SAP_ASSERT(&ioSpread.boxes() == &inBoxes, "the small frame reads the spread of other boxes");
  prepareSweep(inBoxes, ioSpread, chooseSmallFrameAxis(ioSpread), ioWork);
  inSweep(inBoxes, ioWork, outPairs);
  sortPairsCanonical(outPairs, ioWork.pair_scratch);
}

}  // namespace

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

void pairSmallFrame(const BoxSet& inBoxes, FrameSpread& ioSpread, SmallFrameWorkspace& ioWork,
                    PairList& outPairs) {
#if SAP_SMALL_FRAME_AVX2
  if (cpuHasAvx2()) return pairWith(inBoxes, ioSpread, ioWork, outPairs, sweepAvx2);
#endif
  pairWith(inBoxes, ioSpread, ioWork, outPairs, sweepPortable);
}

void pairSmallFrame(const BoxSet& inBoxes, SmallFrameWorkspace& ioWork, PairList& outPairs) {
  FrameSpread spread(inBoxes);
  pairSmallFrame(inBoxes, spread, ioWork, outPairs);
}

void pairSmallFramePortable(const BoxSet& inBoxes, SmallFrameWorkspace& ioWork,
                            PairList& outPairs) {
  FrameSpread spread(inBoxes);
  pairWith(inBoxes, spread, ioWork, outPairs, sweepPortable);
}

}  // namespace sap_broadphase
