// Sort keys (order-preserving, one key for both zeros, outward rounding) and the radix index
// sorts (sequential and Algorithm 2's partitioned sort) against std::stable_sort, on adversarial
// keys: +-0, +-inf, subnormals, many equal keys, magnitudes 1e-300..1e300.
#include <gtest/gtest.h>

#include <algorithm>
#include <cmath>
#include <cstring>
#include <ios>
#include <limits>
#include <numeric>
#include <random>
#include <vector>

#include "core/runner/work_units.h"
#include "core/sweep/radix_sort.h"
#include "core/sweep/sort_keys.h"
#include "test_support.h"

namespace sap_broadphase {
namespace {

using test_support::TestRandom;

constexpr double kInf = std::numeric_limits<double>::infinity();

/// Doubles that stress float32 rounding and key order.
std::vector<double> adversarialDoubles(std::size_t inRandomCount, uint64_t inSeed) {
  std::vector<double> values = {0.0,
                                -0.0,
                                kInf,
                                -kInf,
                                std::numeric_limits<double>::denorm_min(),
                                -std::numeric_limits<double>::denorm_min(),
                                std::numeric_limits<double>::min(),
                                -std::numeric_limits<double>::min(),
                                std::numeric_limits<double>::max(),
                                -std::numeric_limits<double>::max(),
                                std::numeric_limits<float>::denorm_min(),
                                -std::numeric_limits<float>::denorm_min(),
                                std::numeric_limits<float>::denorm_min() / 2,
                                std::numeric_limits<float>::min(),
                                std::numeric_limits<float>::max(),
                                -std::numeric_limits<float>::max(),
                                static_cast<double>(std::numeric_limits<float>::max()) * 1.0000001,
                                -static_cast<double>(std::numeric_limits<float>::max()) * 1.0000001,
                                1.0,
                                -1.0,
                                0.1,
                                -0.1,
                                1.0 + 1e-12,
                                1.0 - 1e-12,
                                1e-300,
                                -1e-300,
                                1e300,
                                -1e300,
                                1e-45,
                                1e-46,
                                16777217.0,
                                -16777217.0};
  TestRandom random(inSeed);
  for (std::size_t k = 0; k < inRandomCount; ++k) {
    const double magnitude = std::pow(10.0, random.between(-300.0, 300.0));
    double value = random.below(2) ? magnitude : -magnitude;
    switch (random.below(5)) {
      case 0:
        value = values[random.below(values.size())];
        break;  // many equal keys
      case 1: {
        uint64_t bits = random.bits();
        std::memcpy(&value, &bits, sizeof value);
        if (std::isnan(value)) value = 0.5;
        break;
      }
      default:
        break;
    }
    values.push_back(value);
  }
  return values;
}

TEST(SortKeys, FloatKeysPreserveOrderAndMergeZeros) {
  EXPECT_EQ(floatToKey(0.0f), floatToKey(-0.0f));
  EXPECT_LT(floatToKey(-std::numeric_limits<float>::infinity()), floatToKey(-1.0f));
  EXPECT_LT(floatToKey(std::numeric_limits<float>::max()),
            floatToKey(std::numeric_limits<float>::infinity()));
  EXPECT_LT(floatToKey(-std::numeric_limits<float>::denorm_min()), floatToKey(0.0f));
  EXPECT_LT(floatToKey(0.0f), floatToKey(std::numeric_limits<float>::denorm_min()));
  TestRandom random(1);
  for (int k = 0; k < 200000; ++k) {
    uint32_t bitsA = static_cast<uint32_t>(random.bits());
    uint32_t bitsB = static_cast<uint32_t>(random.bits());
    float a;
    float b;
    std::memcpy(&a, &bitsA, sizeof a);
    std::memcpy(&b, &bitsB, sizeof b);
    if (std::isnan(a) || std::isnan(b)) continue;
    ASSERT_EQ(a < b, floatToKey(a) < floatToKey(b)) << a << " " << b;
    ASSERT_EQ(a == b, floatToKey(a) == floatToKey(b)) << a << " " << b;
    if (a != 0.0f) {
      ASSERT_EQ(keyToFloat(floatToKey(a)), a);
    }
  }
  EXPECT_EQ(keyToFloat(floatToKey(-0.0f)), 0.0f);
}

TEST(SortKeys, OutwardRoundingBracketsTheExactValue) {
  for (double value : adversarialDoubles(100000, 2)) {
    const float down = keyToFloat(lowKey(value));
    const float up = keyToFloat(highKey(value));
    ASSERT_LE(static_cast<double>(down), value) << value;
    ASSERT_GE(static_cast<double>(up), value) << value;
    ASSERT_LE(lowKey(value), highKey(value)) << value;
    // Tight: the next float beyond the rounded one is on the other side of the value.
    if (static_cast<double>(down) != value && down != std::numeric_limits<float>::max()) {
      ASSERT_GT(static_cast<double>(std::nextafter(down, std::numeric_limits<float>::infinity())),
                value);
    }
    if (static_cast<double>(up) != value && up != -std::numeric_limits<float>::max()) {
      ASSERT_LT(static_cast<double>(std::nextafter(up, -std::numeric_limits<float>::infinity())),
                value);
    }
  }
  EXPECT_EQ(lowKey(0.0), lowKey(-0.0));
  EXPECT_EQ(highKey(0.0), highKey(-0.0));
  EXPECT_EQ(lowKey(0.0), highKey(-0.0));
  EXPECT_EQ(keyToFloat(lowKey(-kInf)), -std::numeric_limits<float>::infinity());
  EXPECT_EQ(keyToFloat(highKey(kInf)), std::numeric_limits<float>::infinity());
  EXPECT_EQ(keyToFloat(highKey(1e300)), std::numeric_limits<float>::infinity());
  EXPECT_EQ(keyToFloat(lowKey(1e300)), std::numeric_limits<float>::max());
  EXPECT_EQ(keyToFloat(lowKey(-1e300)), -std::numeric_limits<float>::infinity());
}

TEST(SortKeys, KeysAreMonotoneInTheDoubleValue) {
  std::vector<double> values = adversarialDoubles(50000, 3);
  std::sort(values.begin(), values.end());
  for (std::size_t k = 1; k < values.size(); ++k) {
    ASSERT_LE(lowKey(values[k - 1]), lowKey(values[k])) << values[k - 1] << " " << values[k];
    ASSERT_LE(highKey(values[k - 1]), highKey(values[k])) << values[k - 1] << " " << values[k];
  }
}

TEST(SortKeys, OverlappingIntervalsOverlapInKeySpace) {
  // The superset property: min_a <= max_b implies lowKey(min_a) <= highKey(max_b).
  const std::vector<double> values = adversarialDoubles(3000, 4);
  for (double a : values) {
    for (std::size_t k = 0; k < values.size(); k += 7) {
      if (a <= values[k]) {
        ASSERT_LE(lowKey(a), highKey(values[k])) << a << " " << values[k];
      }
    }
  }
}

/// The expected index order: stable sort of indexes by key.
std::vector<uint32_t> stableOrder(const std::vector<uint32_t>& inKeys) {
  std::vector<uint32_t> order(inKeys.size());
  std::iota(order.begin(), order.end(), 0u);
  std::stable_sort(order.begin(), order.end(),
                   [&](uint32_t a, uint32_t b) { return inKeys[a] < inKeys[b]; });
  return order;
}

/// Endpoint keys as the engine builds them: lows (rounded down) at i, highs (up) at i + n.
std::vector<uint32_t> endpointKeys(const std::vector<double>& inValues, uint64_t inSeed) {
  TestRandom random(inSeed);
  const std::size_t n = inValues.size();
  std::vector<uint32_t> keys(2 * n);
  for (std::size_t i = 0; i < n; ++i) {
    const double other = inValues[random.below(n)];
    const double low = std::min(inValues[i], other);
    const double high = random.below(4) == 0 ? low : std::max(inValues[i], other);
    keys[i] = lowKey(low);
    keys[i + n] = highKey(high);
  }
  return keys;
}

/// Key sets to sort: adversarial endpoints, raw random bits, few distinct keys, all equal.
std::vector<std::vector<uint32_t>> keySets() {
  std::vector<std::vector<uint32_t>> sets;
  sets.push_back({});
  sets.push_back({42});
  sets.push_back({7, 7});
  sets.push_back({9, 3});
  sets.push_back(endpointKeys(adversarialDoubles(20000, 5), 6));
  TestRandom random(7);
  std::vector<uint32_t> rawBits(100003);
  for (uint32_t& key : rawBits) key = static_cast<uint32_t>(random.bits());
  sets.push_back(rawBits);
  std::vector<uint32_t> fewDistinct(70000);
  for (uint32_t& key : fewDistinct) key = lowKey(static_cast<double>(random.below(5)) - 2.0);
  sets.push_back(fewDistinct);
  sets.push_back(std::vector<uint32_t>(5000, 0x80000000u));
  std::vector<uint32_t> highDigitsOnly(40000);  // only the top digit differs
  for (uint32_t& key : highDigitsOnly) key = static_cast<uint32_t>(random.below(4)) << 30;
  sets.push_back(highDigitsOnly);
  std::vector<uint32_t> descending(30000);
  for (std::size_t k = 0; k < descending.size(); ++k)
    descending[k] = static_cast<uint32_t>(descending.size() - k);
  sets.push_back(descending);
  return sets;
}

TEST(RadixSort, IndexSortEqualsStableSort) {
  for (const std::vector<uint32_t>& keys : keySets()) {
    std::vector<uint32_t> order(keys.size());
    radixIndexSort(keys.data(), static_cast<uint32_t>(keys.size()), order.data());
    ASSERT_EQ(order, stableOrder(keys)) << keys.size() << " keys";
  }
}

TEST(RadixSort, PackedSortIsStable) {
  for (const std::vector<uint32_t>& keys : keySets()) {
    std::vector<uint64_t> items(keys.size());
    std::vector<uint64_t> scratch(keys.size());
    for (std::size_t k = 0; k < keys.size(); ++k)
      items[k] = packKeyIndex(keys[k], static_cast<uint32_t>(k));
    const uint64_t* sorted = radixSortPacked(items.data(), scratch.data(), items.size());
    ASSERT_TRUE(sorted == items.data() || sorted == scratch.data());
    const std::vector<uint32_t> expected = stableOrder(keys);
    for (std::size_t k = 0; k < keys.size(); ++k)
      ASSERT_EQ(static_cast<uint32_t>(sorted[k]), expected[k]) << k;
  }
}

// Key sets below and above the parallel sort's size (2^19 items; the larger one is several
// units of kUnitBoxes a thread): random keys, few distinct keys, keys whose digits vary only in
// the top or only in the lowest pass (the other passes skipped), and keys already in order.
std::vector<std::vector<uint32_t>> multiUnitKeySets() {
  TestRandom random(2024);
  std::vector<std::vector<uint32_t>> sets;
  for (std::size_t count : {2 * kUnitBoxes, (std::size_t{1} << 19) + 17}) {
    std::vector<uint32_t> keys(count);
    for (uint32_t& key : keys) key = static_cast<uint32_t>(random.bits());
    sets.push_back(keys);
    for (uint32_t& key : keys) key = static_cast<uint32_t>(random.below(5)) * 0x01010101u;
    sets.push_back(keys);
    for (uint32_t& key : keys) key = static_cast<uint32_t>(random.below(1024)) << 22;
    sets.push_back(keys);
    for (uint32_t& key : keys) key = 0xABC00000u | static_cast<uint32_t>(random.below(2048));
    sets.push_back(keys);
    for (std::size_t k = 0; k < count; ++k) keys[k] = lowKey(static_cast<double>(k) - 1000.0);
    sets.push_back(keys);
  }
  return sets;
}

// The packed sort on 1 to 4 threads of a scope, and inside a unit of a pass (where it runs
// serially): the stable order every time.
TEST(RadixSort, PackedSortIsStableOnAnyThreadCount) {
  for (const std::vector<uint32_t>& keys : multiUnitKeySets()) {
    const std::vector<uint32_t> expected = stableOrder(keys);
    for (int threads = 1; threads <= 4; ++threads) {
      const ThreadsScope scope(threads);
      for (bool in_unit : {false, true}) {
        std::vector<uint64_t> items(keys.size());
        std::vector<uint64_t> scratch(keys.size());
        for (std::size_t k = 0; k < keys.size(); ++k)
          items[k] = packKeyIndex(keys[k], static_cast<uint32_t>(k));
        const uint64_t* sorted = nullptr;
        if (in_unit)
          runUnits(2, [&](std::size_t inUnit) {
            if (inUnit == 0) sorted = radixSortPacked(items.data(), scratch.data(), items.size());
          });
        else
          sorted = radixSortPacked(items.data(), scratch.data(), items.size());
        ASSERT_TRUE(sorted == items.data() || sorted == scratch.data());
        for (std::size_t k = 0; k < keys.size(); ++k)
          ASSERT_EQ(static_cast<uint32_t>(sorted[k]), expected[k])
              << keys.size() << " keys, " << threads << " threads, in a unit: " << in_unit
              << ", rank " << k;
      }
    }
  }
}

TEST(RadixSort, LowEndpointsComeBeforeHighEndpointsAtEqualCoordinates) {
  // Closed intervals: object i's low (index i) precedes any high (index >= n) with the same key.
  const std::vector<double> values = {1.0, 1.0, 1.0, 2.0, 0.0, -0.0};
  const std::size_t n = values.size();
  std::vector<uint32_t> keys(2 * n);
  for (std::size_t i = 0; i < n; ++i) {
    keys[i] = lowKey(values[i]);
    keys[i + n] = highKey(values[i]);  // zero-extent boxes
  }
  std::vector<uint32_t> order(2 * n);
  radixIndexSort(keys.data(), static_cast<uint32_t>(2 * n), order.data());
  for (std::size_t k = 1; k < order.size(); ++k) {
    if (keys[order[k]] == keys[order[k - 1]] && order[k] < n) {
      EXPECT_LT(order[k - 1], n) << "a high endpoint precedes a low one at the same key";
    }
  }
}

TEST(RadixSort, PartitionedSortEqualsStableSortAcrossFrames) {
  for (const std::vector<uint32_t>& baseKeys : keySets()) {
    for (int partitions : {1, 2, 3, 4, 7, 16}) {
      for (int threads : {1, 2, 7}) {
        const ThreadsScope scope(threads);
        PartitionedSorter sorter;
        AxisBounds bounds;
        std::vector<uint32_t> keys = baseKeys;
        TestRandom random(static_cast<uint64_t>(partitions * 31 + threads));
        for (int frame = 0; frame < 3; ++frame) {
          std::vector<uint32_t> order(keys.size());
          const double dispersion = sorter.sort(keys.data(), static_cast<uint32_t>(keys.size()),
                                                partitions, bounds, order.data());
          ASSERT_EQ(order, stableOrder(keys))
              << keys.size() << " keys, " << partitions << " partitions, " << threads
              << " threads, frame " << frame;
          ASSERT_TRUE(std::isfinite(dispersion));
          ASSERT_GE(dispersion, 0.0);
          if (!keys.empty()) {
            EXPECT_TRUE(bounds.from_previous_frame);
            EXPECT_TRUE(std::is_sorted(bounds.bounds.begin(), bounds.bounds.end()));
          }
          // Next frame: small moves for most keys, big jumps for a few.
          for (uint32_t& key : keys) {
            const uint64_t move = random.below(100);
            if (move < 3)
              key = static_cast<uint32_t>(random.bits());
            else if (move < 50 && key < 0xFFFFFF00u)
              key += static_cast<uint32_t>(move);
          }
        }
      }
    }
  }
}

TEST(RadixSort, PartitionedSortHandlesSizeChangesBetweenFrames) {
  const ThreadsScope two_threads(2);
  PartitionedSorter sorter;
  AxisBounds bounds;
  TestRandom random(99);
  for (std::size_t count : {1000u, 10u, 0u, 5000u, 1u, 3000u}) {
    std::vector<uint32_t> keys(count);
    for (uint32_t& key : keys) key = lowKey(random.between(-10.0, 10.0));
    std::vector<uint32_t> order(count);
    sorter.sort(keys.data(), static_cast<uint32_t>(count), 4, bounds, order.data());
    ASSERT_EQ(order, stableOrder(keys)) << count;
  }
}

TEST(RadixSort, DispersionIsZeroForBalancedPartitionsAndHighWhenClustered) {
  // Frame 1 sets B from the sorted order; frame 2 with the same keys is then perfectly balanced.
  const ThreadsScope two_threads(2);
  std::vector<uint32_t> keys(40000);
  for (std::size_t k = 0; k < keys.size(); ++k) keys[k] = lowKey(static_cast<double>(k));
  PartitionedSorter sorter;
  AxisBounds bounds;
  std::vector<uint32_t> order(keys.size());
  sorter.sort(keys.data(), static_cast<uint32_t>(keys.size()), 4, bounds, order.data());
  const double balanced =
      sorter.sort(keys.data(), static_cast<uint32_t>(keys.size()), 4, bounds, order.data());
  EXPECT_LT(balanced, 0.01);
  // Now every key collapses onto one value: all land in one partition.
  std::fill(keys.begin(), keys.end(), lowKey(12345.0));
  const double clustered =
      sorter.sort(keys.data(), static_cast<uint32_t>(keys.size()), 4, bounds, order.data());
  EXPECT_GT(clustered, 0.5);
  EXPECT_EQ(order, stableOrder(keys));
}

}  // namespace
}  // namespace sap_broadphase

namespace sap_broadphase {
namespace {

// lowKey/highKey step keys instead of calling nextafter; they must equal the keys of the
// nextafter-based roundings on every double, near zero, subnormals and the float range's ends.
TEST(SortKeys, FastKeysEqualTheKeysOfTheDirectedRoundings) {
  std::mt19937_64 random(20261121);
  std::vector<double> values = {0.0,
                                -0.0,
                                5e-324,
                                -5e-324,
                                0x1p-149,
                                -0x1p-149,
                                0x1p-150,
                                -0x1p-150,
                                0x1.8p-150,
                                -0x1.8p-150,
                                3.4028235e38,
                                -3.4028235e38,
                                3.5e38,
                                -3.5e38,
                                1e300,
                                -1e300,
                                std::numeric_limits<double>::infinity(),
                                -std::numeric_limits<double>::infinity()};
  for (int k = 0; k < 300000; ++k) {
    const uint64_t bits = random();
    double value;
    std::memcpy(&value, &bits, sizeof value);
    if (!std::isnan(value)) values.push_back(value);
    const uint32_t float_bits = static_cast<uint32_t>(random());
    float single;
    std::memcpy(&single, &float_bits, sizeof single);
    if (std::isnan(single)) continue;
    values.push_back(single);
    values.push_back(std::nextafter(static_cast<double>(single), 1e308));
    values.push_back(std::nextafter(static_cast<double>(single), -1e308));
  }
  for (double value : values) {
    ASSERT_EQ(lowKey(value), floatToKey(roundDownToFloat(value))) << std::hexfloat << value;
    ASSERT_EQ(highKey(value), floatToKey(roundUpToFloat(value))) << std::hexfloat << value;
  }
}

}  // namespace
}  // namespace sap_broadphase
