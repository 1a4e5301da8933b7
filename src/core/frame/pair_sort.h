// The engine's pair lists on their way out: the pairing threads' chunked lists and the sorts
// that put pairs in canonical order (pair_set.h), once a frame.
#pragma once

#include <atomic>
#include <cstddef>
#include <cstdint>
#include <memory>
#include <utility>
#include <vector>

#include "core/runner/buffers.h"
#include "core/tuning.h"
#include "sap_broadphase/core/pair_set.h"

namespace sap_broadphase {

/// The most pairs the pairing threads of one frame may find together
/// (BroadphaseConfig::max_pairs). Each thread's PairChunks counts a chunk here once it is full,
/// and the count past the bound throws TooManyPairs: the threads stop within a chunk each of
/// it, instead of holding pairs until memory runs out. A full chunk is a chunk of pairs found,
/// so a frame with at most the bound's pairs never throws.
class PairBudget {
 public:
  /// A budget of inLimit pairs, none counted yet.
  explicit PairBudget(std::size_t inLimit) : limit_(inLimit) {}
  PairBudget(const PairBudget&) = delete;
  PairBudget& operator=(const PairBudget&) = delete;
  /// Counts inPairs more pairs found; throws TooManyPairs once the count passes the limit.
  void count(std::size_t inPairs);
  /// True once a count passed the limit: the pass's units not yet started do nothing (a unit
  /// that threw left its worker's state half-swept, and the frame is refused anyway).
  bool exhausted() const { return found_.load(std::memory_order_relaxed) > limit_; }

 private:
  const std::size_t limit_;
  std::atomic<std::size_t> found_{0};
};

/// Pairs appended in fixed-size chunks, the pairing threads' output: growing never copies
/// (a vector's doubling would keep old and new storage resident together) and clear() keeps
/// the chunks for the next frame. A chunk is a BufferAllocator allocation (64 KiB: a block of
/// BufferCache, so a fresh engine's chunks are resident where an engine ran before).
class PairChunks {
 public:
  static constexpr std::size_t kChunkPairs = tuning::kPairChunkPairs;

  PairChunks() = default;
  PairChunks(PairChunks&& ioOther) noexcept
      : chunks_(std::move(ioOther.chunks_)),
        used_chunks_(std::exchange(ioOther.used_chunks_, 0)),
        fill_(std::exchange(ioOther.fill_, kChunkPairs)) {}
  PairChunks& operator=(PairChunks&& ioOther) noexcept {
    if (this != &ioOther) {
      releaseChunks();
      chunks_ = std::move(ioOther.chunks_);
      used_chunks_ = std::exchange(ioOther.used_chunks_, 0);
      fill_ = std::exchange(ioOther.fill_, kChunkPairs);
    }
    return *this;
  }
  PairChunks(const PairChunks&) = delete;
  PairChunks& operator=(const PairChunks&) = delete;
  ~PairChunks() { releaseChunks(); }

  /// Forgets the pairs, keeping the storage.
  void clear() {
    used_chunks_ = 0;
    fill_ = kChunkPairs;
  }
  /// The budget each full chunk is counted against (null: none); set by the pass that fills
  /// the list, for that pass.
  void setBudget(PairBudget* inBudget) { budget_ = inBudget; }
  /// Appends one pair.
  void push_back(const IdPair& inPair) {
    if (fill_ == kChunkPairs) startChunk();
    chunks_[used_chunks_ - 1][fill_++] = inPair;
  }
  /// Number of pairs held.
  std::size_t size() const {
    return used_chunks_ == 0 ? 0 : (used_chunks_ - 1) * kChunkPairs + fill_;
  }
  /// Bytes of the chunks held (used or kept for reuse).
  std::size_t bytesHeld() const { return chunks_.size() * kChunkPairs * sizeof(IdPair); }
  /// Calls inVisit(pair) for every pair, in insertion order.
  template <typename Visit>
  void forEach(Visit&& inVisit) const {
    for (std::size_t chunk = 0; chunk < used_chunks_; ++chunk) {
      const std::size_t count = chunk + 1 == used_chunks_ ? fill_ : kChunkPairs;
      const IdPair* pairs = chunks_[chunk];
      for (std::size_t k = 0; k < count; ++k) inVisit(pairs[k]);
    }
  }

 private:
  void startChunk();
  void releaseChunks();

  std::vector<IdPair*> chunks_;  // each kChunkPairs pairs from BufferAllocator<IdPair>
  std::size_t used_chunks_ = 0;
  std::size_t fill_ = kChunkPairs;
  PairBudget* budget_ = nullptr;
};

/// Takes the budget out of every list of ioLists when it leaves scope, thrown out of or not: a
/// pass's budget lives on its stack.
class BudgetScope {
 public:
  explicit BudgetScope(std::vector<PairChunks>& ioLists) : lists_(ioLists) {}
  ~BudgetScope() {
    for (PairChunks& pairs : lists_) pairs.setBudget(nullptr);
  }
  BudgetScope(const BudgetScope&) = delete;
  BudgetScope& operator=(const BudgetScope&) = delete;

 private:
  std::vector<PairChunks>& lists_;
};

/// Buffers reused by sortPairsCanonical between calls.
struct PairSortScratch {
  PairList pairs;
  Buffer<uint32_t> offsets;  // every sort fills what it reads: growing it zeroes nothing
};

/// Sorts pairs by (a, b), whatever the order within a pair (box queries' (query id, world id)
/// hits). Dense ids (largest a below a few times the pair count): a counting sort on a, then
/// each a's short list sorted by b. Sparse ids: an LSD radix sort on the 64-bit key a<<32|b.
void sortPairsByAThenB(PairList& ioPairs, PairSortScratch& ioScratch);
/// The same for pairs with a < b: the canonical order used wherever pairs leave the process.
void sortPairsCanonical(PairList& ioPairs, PairSortScratch& ioScratch);
/// Convenience overload with temporary buffers.
void sortPairsCanonical(PairList& ioPairs);
/// Merges the disjoint lists inParts into outPairs in canonical order, without first copying
/// them into one list when ids are dense. inParts is left unchanged. On the threads of the
/// runner's scope (one part each), so the merge grows with n on every core rather than on one;
/// the same result for any thread count.
void sortPairsCanonical(const std::vector<PairChunks>& inParts, PairList& outPairs,
                        PairSortScratch& ioScratch);

}  // namespace sap_broadphase
