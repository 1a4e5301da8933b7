// SuccTree against a std::set model: random operations up to n = 2^20, the symmetric
// difference, iteration order and range bounds.
#include <gtest/gtest.h>

#include <algorithm>
#include <cstdlib>
#include <iterator>
#include <set>
#include <vector>

#include "core/sweep/succ_tree.h"
#include "test_support.h"

namespace sap_broadphase {
namespace {

using test_support::TestRandom;

/// Every element of inTree in [inBegin, inEnd), via forEachInRange.
std::vector<uint32_t> rangeOf(const SuccTree& inTree, uint32_t inBegin, uint32_t inEnd) {
  std::vector<uint32_t> values;
  inTree.forEachInRange(inBegin, inEnd, [&](uint32_t inValue) { values.push_back(inValue); });
  return values;
}

/// The model's elements in [inBegin, inEnd).
std::vector<uint32_t> rangeOf(const std::set<uint32_t>& inModel, uint32_t inBegin, uint32_t inEnd) {
  if (inBegin >= inEnd) return {};
  return std::vector<uint32_t>(inModel.lower_bound(inBegin), inModel.lower_bound(inEnd));
}

/// Full comparison of tree and model (O(n)).
void expectSame(const SuccTree& inTree, const std::set<uint32_t>& inModel) {
  ASSERT_EQ(inTree.empty(), inModel.empty());
  ASSERT_EQ(inTree.min(), inModel.empty() ? SuccTree::kNone : *inModel.begin());
  ASSERT_EQ(rangeOf(inTree, 0, inTree.size()),
            std::vector<uint32_t>(inModel.begin(), inModel.end()));
}

/// Model answer of next(inValue).
uint32_t modelNext(const std::set<uint32_t>& inModel, uint32_t inValue) {
  const auto found = inModel.lower_bound(inValue);
  return found == inModel.end() ? SuccTree::kNone : *found;
}

/// A value biased towards word and block boundaries, where bugs live.
uint32_t pickValue(TestRandom& ioRandom, uint32_t inSize) {
  const uint64_t choice = ioRandom.below(4);
  if (choice == 0) {
    const uint32_t boundary = static_cast<uint32_t>(64u << (6 * ioRandom.below(3)));
    const uint32_t base = static_cast<uint32_t>(ioRandom.below(inSize / boundary + 1)) * boundary;
    const uint32_t value = base + static_cast<uint32_t>(ioRandom.below(3)) - 1u;
    return value < inSize ? value : static_cast<uint32_t>(ioRandom.below(inSize));
  }
  if (choice == 1) return inSize - 1 - static_cast<uint32_t>(ioRandom.below(std::min(inSize, 3u)));
  return static_cast<uint32_t>(ioRandom.below(inSize));
}

/// Random inserts, erases, toggles and queries on a tree of inSize, checked against the model.
void randomOperations(uint32_t inSize, int inOperations, uint64_t inSeed) {
  TestRandom random(inSeed);
  SuccTree tree(inSize);
  std::set<uint32_t> model;
  expectSame(tree, model);
  for (int step = 0; step < inOperations; ++step) {
    const uint32_t value = pickValue(random, inSize);
    switch (random.below(6)) {
      case 0:
      case 1:
        tree.insert(value);
        model.insert(value);
        break;
      case 2:
        tree.erase(value);
        model.erase(value);
        break;
      case 3:
        tree.toggle(value);
        if (!model.erase(value)) model.insert(value);
        break;
      case 4:
        ASSERT_EQ(tree.contains(value), model.count(value) == 1) << value;
        ASSERT_EQ(tree.next(value), modelNext(model, value)) << "next(" << value << ")";
        break;
      default: {
        const uint32_t begin = pickValue(random, inSize);
        const uint32_t end =
            std::min<uint64_t>(inSize, begin + random.below(random.below(16) == 0 ? 70000 : 300));
        ASSERT_EQ(rangeOf(tree, begin, end), rangeOf(model, begin, end))
            << "range [" << begin << ", " << end << ")";
        break;
      }
    }
    ASSERT_EQ(tree.min(), model.empty() ? SuccTree::kNone : *model.begin());
  }
  expectSame(tree, model);
  // Erase everything through the model: the tree must end up empty.
  for (uint32_t value : model) tree.erase(value);
  EXPECT_TRUE(tree.empty());
  EXPECT_EQ(tree.min(), SuccTree::kNone);
}

TEST(SuccTree, RandomOperationsSmallUniverses) {
  for (uint32_t size : {1u, 2u, 63u, 64u, 65u, 127u, 128u, 4095u, 4096u, 4097u}) {
    SCOPED_TRACE(size);
    randomOperations(size, 20000, size);
  }
}

TEST(SuccTree, RandomOperationsLargeUniverses) {
  for (uint32_t size : {262143u, 262145u, 1u << 20}) {
    SCOPED_TRACE(size);
    randomOperations(size, 150000, size + 1);
  }
}

TEST(SuccTree, DenseFillAndDrain) {
  const uint32_t size = (1u << 20);
  SuccTree tree(size);
  for (uint32_t v = 0; v < size; v += 3) tree.insert(v);
  uint32_t expected = 0;
  uint32_t count = 0;
  tree.forEachInRange(0, size, [&](uint32_t inValue) {
    EXPECT_EQ(inValue, expected);
    expected += 3;
    ++count;
  });
  EXPECT_EQ(count, (size + 2) / 3);
  for (uint32_t v = 0; v < size; v += 3) {
    ASSERT_EQ(tree.min(), v);
    tree.erase(v);
  }
  EXPECT_TRUE(tree.empty());
}

TEST(SuccTree, NextWalksInIncreasingOrder) {
  TestRandom random(3);
  const uint32_t size = 300000;
  SuccTree tree(size);
  std::set<uint32_t> model;
  for (int k = 0; k < 5000; ++k) {
    const uint32_t value = static_cast<uint32_t>(random.below(size));
    tree.insert(value);
    model.insert(value);
  }
  std::vector<uint32_t> walked;
  for (uint32_t v = tree.min(); v != SuccTree::kNone;
       v = v + 1 < size ? tree.next(v + 1) : SuccTree::kNone)
    walked.push_back(v);
  EXPECT_EQ(walked, std::vector<uint32_t>(model.begin(), model.end()));
}

TEST(SuccTree, RangeBoundsAreHalfOpen) {
  const uint32_t size = 5000;
  SuccTree tree(size);
  std::set<uint32_t> model;
  for (uint32_t v : {0u, 1u, 62u, 63u, 64u, 65u, 127u, 128u, 4095u, 4096u, 4097u, 4999u}) {
    tree.insert(v);
    model.insert(v);
  }
  const uint32_t bounds[] = {0,   1,   2,    62,   63,   64,   65,   66,  127,
                             128, 129, 4095, 4096, 4097, 4998, 4999, 5000};
  for (uint32_t begin : bounds)
    for (uint32_t end : bounds)
      EXPECT_EQ(rangeOf(tree, begin, end), rangeOf(model, begin, end))
          << "[" << begin << ", " << end << ")";
}

/// A random subset of {0..inSize-1} with about inCount elements, as tree and model.
void randomSubset(uint32_t inSize, uint32_t inCount, TestRandom& ioRandom, SuccTree& outTree,
                  std::set<uint32_t>& outModel) {
  outTree.resize(inSize);
  outModel.clear();
  for (uint32_t k = 0; k < inCount; ++k) {
    const uint32_t value = pickValue(ioRandom, inSize);
    outTree.insert(value);
    outModel.insert(value);
  }
}

TEST(SuccTree, SymmetricDifferenceMatchesTheModel) {
  TestRandom random(17);
  for (uint32_t size : {1u, 64u, 65u, 4096u, 4160u, 100000u, 1u << 20}) {
    for (uint32_t count : {0u, 1u, 50u, 3000u}) {
      SuccTree a;
      SuccTree b;
      std::set<uint32_t> modelA;
      std::set<uint32_t> modelB;
      randomSubset(size, count, random, a, modelA);
      randomSubset(size, count / 2 + 1, random, b, modelB);
      // Make sure some elements are shared, so that both union and intersection matter.
      for (uint32_t value : modelA) {
        if (random.below(3) == 0) {
          b.insert(value);
          modelB.insert(value);
        }
      }
      std::set<uint32_t> expected;
      std::set_symmetric_difference(modelA.begin(), modelA.end(), modelB.begin(), modelB.end(),
                                    std::inserter(expected, expected.end()));
      a.symmetricDifference(b);
      SCOPED_TRACE(testing::Message() << "size " << size << " count " << count);
      expectSame(a, expected);
      expectSame(b, modelB);  // the argument is untouched
      // ⊕ with itself empties; ⊕ twice restores.
      SuccTree copy(size);
      copy.assign(a);
      expectSame(copy, expected);
      copy.symmetricDifference(b);
      copy.symmetricDifference(b);
      expectSame(copy, expected);
      copy.symmetricDifference(a);  // copy == a here
      EXPECT_TRUE(copy.empty());
      // The tree still works after ⊕: insert and erase keep upper levels consistent.
      if (!expected.empty()) {
        const uint32_t first = *expected.begin();
        a.erase(first);
        expected.erase(first);
        expectSame(a, expected);
      }
      a.insert(size - 1);
      expected.insert(size - 1);
      expectSame(a, expected);
    }
  }
}

TEST(SuccTree, AllPrefixSymmetricDifferenceOfPartitions) {
  // The paper's Algorithm 3: per-slice toggles, then prefix ⊕ gives the set active at each
  // slice start.
  TestRandom random(23);
  const uint32_t size = 20000;
  const int slices = 7;
  std::vector<SuccTree> local(slices, SuccTree(size));
  std::vector<std::set<uint32_t>> activeAtStart(slices + 1);
  std::set<uint32_t> active;
  for (int s = 0; s < slices; ++s) {
    activeAtStart[s] = active;
    for (int k = 0; k < 3000; ++k) {
      const uint32_t value = static_cast<uint32_t>(random.below(size));
      local[s].toggle(value);
      if (!active.erase(value)) active.insert(value);
    }
  }
  SuccTree prefix(size);
  for (int s = 0; s < slices; ++s) {
    expectSame(prefix, activeAtStart[s]);
    prefix.symmetricDifference(local[s]);
  }
  expectSame(prefix, active);
}

TEST(SuccTree, DefaultConstructedTreeIsAnEmptySizeZeroTree) {
  // Run in a child process: a crash fails this test instead of ending the whole suite. The
  // child re-executes the binary ("threadsafe"): OpenMP's thread pool does not survive fork().
  GTEST_FLAG_SET(death_test_style, "threadsafe");
  EXPECT_EXIT(
      {
        SuccTree a;
        SuccTree b;
        bool ok = a.size() == 0 && a.empty() && a.min() == SuccTree::kNone;
        a.forEachInRange(0, 0, [&](uint32_t) { ok = false; });
        a.symmetricDifference(b);
        a.clear();
        ok = ok && a.empty();
        std::exit(ok ? 0 : 1);
      },
      ::testing::ExitedWithCode(0), "");
}

TEST(SuccTree, ClearAndResizeEmpty) {
  SuccTree tree(100000);
  for (uint32_t v = 0; v < 100000; v += 997) tree.insert(v);
  tree.clear();
  EXPECT_TRUE(tree.empty());
  EXPECT_EQ(rangeOf(tree, 0, tree.size()), std::vector<uint32_t>{});
  tree.insert(5);
  tree.resize(70);
  EXPECT_EQ(tree.size(), 70u);
  EXPECT_TRUE(tree.empty());
  tree.insert(69);
  EXPECT_EQ(tree.min(), 69u);
  tree.resize(1u << 20);
  EXPECT_TRUE(tree.empty());
  tree.insert((1u << 20) - 1);
  EXPECT_EQ(tree.next(0), (1u << 20) - 1);
}

}  // namespace
}  // namespace sap_broadphase
