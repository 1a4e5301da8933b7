// Unchanged-frame reuse: a frame equal to the previous one may return the previous pairs, but
// any change at all (one bit of one bound, an id, a group or mask, the order) must be seen,
// including changes made in place to the very BoxSet the engine saw last.
#include <gtest/gtest.h>

#include <cmath>
#include <limits>
#include <string>
#include <utility>

#include "sap_broadphase/core/brute_force.h"
#include "test_support.h"

namespace sap_broadphase {
namespace {

using test_support::engineConfig;
using test_support::samePairs;

/// An engine configuration with unchanged-frame reuse on (it is off by default).
BroadphaseConfig reusingConfig(Method inMethod, int inThreads) {
  BroadphaseConfig config = engineConfig(inMethod, inThreads, 0, 1);
  config.reuse_unchanged_frames = true;
  return config;
}

/// Boxes on a grid touching their x neighbours exactly (many pairs hinge on one bound).
BoxSet touchingRow(std::size_t inCount) {
  BoxSet boxes;
  for (std::size_t i = 0; i < inCount; ++i) {
    const double x = static_cast<double>(i % 70);
    const double y = static_cast<double>(i / 70) * 0.5;
    const double lo[3] = {x, y, 0.0};
    const double hi[3] = {x + 1.0, y + 0.25, 1.0};
    boxes.add(static_cast<uint32_t>(i * 3 + 1), lo, hi);
  }
  return boxes;
}

/// Runs inChange on a copy of the boxes, in place, between two updates of every engine kind.
template <typename Change>
void expectChangeSeen(const std::string& inLabel, Change&& inChange, bool inFilters = false) {
  for (Method method : {Method::kSequential, Method::kParallel, Method::kAuto}) {
    BoxSet boxes = touchingRow(4900);
    if (inFilters) test_support::addRandomFilters(boxes, 3);
    Broadphase broadphase(reusingConfig(method, 3));
    ASSERT_TRUE(samePairs(bruteForcePairs(boxes), broadphase.update(boxes)));
    ASSERT_TRUE(samePairs(bruteForcePairs(boxes), broadphase.update(boxes)));  // may be reused
    inChange(boxes);
    ASSERT_FALSE(validate(boxes).has_value());
    EXPECT_TRUE(samePairs(bruteForcePairs(boxes), broadphase.update(boxes)))
        << inLabel << ", " << test_support::describe(broadphase.config());
  }
}

TEST(EngineReuse, UnchangedFramesGiveTheSamePairs) {
  BoxSet boxes = touchingRow(4900);
  const PairList oracle = bruteForcePairs(boxes);
  for (Method method : {Method::kSequential, Method::kParallel}) {
    Broadphase broadphase(reusingConfig(method, 2));
    for (int frame = 0; frame < 4; ++frame) {
      const BoxSet copy = boxes;  // equal content, another object
      EXPECT_TRUE(samePairs(oracle, broadphase.update(frame % 2 ? copy : boxes)));
    }
  }
}

TEST(EngineReuse, OneBitOfOneBoundIsAChange) {
  const double kInf = std::numeric_limits<double>::infinity();
  expectChangeSeen("hi_x nudged down one ulp", [&](BoxSet& ioBoxes) {
    ioBoxes.hi(0, 500) = std::nextafter(ioBoxes.hi(0, 500), -kInf);
  });
  expectChangeSeen("lo_x nudged up one ulp", [&](BoxSet& ioBoxes) {
    ioBoxes.lo(0, 501) = std::nextafter(ioBoxes.lo(0, 501), kInf);
  });
  expectChangeSeen("lo_z moved away", [](BoxSet& ioBoxes) {
    ioBoxes.lo(2, 4899) = 5.0;
    ioBoxes.hi(2, 4899) = 6.0;
  });
}

TEST(EngineReuse, IdsOrderAndFiltersAreChanges) {
  expectChangeSeen("one id renamed", [](BoxSet& ioBoxes) { ioBoxes.ids[123] = 999999u; });
  expectChangeSeen("two boxes swapped in order", [](BoxSet& ioBoxes) {
    std::swap(ioBoxes.ids[10], ioBoxes.ids[4000]);
    for (int axis = 0; axis < 3; ++axis) {
      std::swap(ioBoxes.lo(axis, 10), ioBoxes.lo(axis, 4000));
      std::swap(ioBoxes.hi(axis, 10), ioBoxes.hi(axis, 4000));
    }
  });
  expectChangeSeen("ids swapped, bounds kept",
                   [](BoxSet& ioBoxes) { std::swap(ioBoxes.ids[10], ioBoxes.ids[11]); });
  expectChangeSeen("filters added",
                   [](BoxSet& ioBoxes) { test_support::addRandomFilters(ioBoxes, 9); });
  expectChangeSeen(
      "filters removed",
      [](BoxSet& ioBoxes) {
        ioBoxes.groups.clear();
        ioBoxes.masks.clear();
      },
      true);
  expectChangeSeen(
      "one mask changed", [](BoxSet& ioBoxes) { ioBoxes.masks[77] ^= 0x7u; }, true);
  expectChangeSeen(
      "one mask set to zero", [](BoxSet& ioBoxes) { ioBoxes.masks[78] = 0; }, true);
  expectChangeSeen(
      "a zero mask made non-zero",
      [](BoxSet& ioBoxes) {
        for (std::size_t i = 0; i < ioBoxes.size(); ++i)
          if (ioBoxes.masks[i] == 0) ioBoxes.masks[i] = 0xFFu;
      },
      true);
  expectChangeSeen("one box removed", [](BoxSet& ioBoxes) {
    ioBoxes.ids.pop_back();
    ioBoxes.bounds.resize(ioBoxes.bounds.size() - kBoundsPerBox);
  });
}

}  // namespace
}  // namespace sap_broadphase
