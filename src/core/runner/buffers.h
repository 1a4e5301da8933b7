// Buffers that every frame overwrites.
#pragma once

#include <cstddef>
#include <cstdint>
#include <cstdlib>
#include <cstring>
#include <memory>
#include <mutex>
#include <new>
#include <type_traits>
#include <utility>
#include <vector>

#include "core/assert.h"

#if defined(__linux__)
#include <sys/mman.h>
#endif

namespace sap_broadphase {

/// Bytes of a cache line: per-thread counters placed this far apart never share one.
constexpr std::size_t kCacheLineBytes = 64;

/// Blocks of 64 KiB to 2 MiB that buffers gave back, kept for the next buffer of their size
/// class, process-wide and bounded (kCacheBytes): a fresh engine in a process that ran one
/// before then finds its buffers resident. Without it, glibc returns the top of its heap to the
/// system when an engine's buffers are freed, and the next engine faults every page again:
/// measured on the 2-core VM (2^14 boxes, one thread, a fresh engine a frame), 0.86 against a
/// warm frame's 0.72 ms at d = 0.05, 2.03 against 1.59 at d = 0.35; with the heap never trimmed
/// (mallopt, which a library must not set for its process), 0.56 and 1.46.
class BufferCache {
 public:
  static constexpr std::size_t kSmallestBytes = std::size_t{64} << 10;
  static constexpr std::size_t kLargestBytes = std::size_t{2} << 20;  ///< exclusive
  static constexpr std::size_t kCacheBytes = std::size_t{4} << 20;
  static constexpr std::size_t kAlignment = kCacheLineBytes;

  /// True for a size the cache serves.
  static bool serves(std::size_t inBytes) {
    return inBytes >= kSmallestBytes && inBytes < kLargestBytes;
  }
  /// A block of at least inBytes (a size served), aligned to kAlignment: a kept one of its class
  /// if any, else a new one of the class's size.
  static void* take(std::size_t inBytes) {
    SAP_ASSERT(serves(inBytes), "a block the cache does not serve");
    const int size_class = classOf(inBytes);
    SAP_ASSERT(classBytes(size_class) >= inBytes, "a block smaller than asked for");
    BufferCache& cache = instance();
    {
      const std::lock_guard<std::mutex> lock(cache.mutex_);
      std::vector<void*>& kept = cache.kept_[size_class];
      if (!kept.empty()) {
        void* block = kept.back();
        kept.pop_back();
        cache.bytes_ -= classBytes(size_class);
        return block;
      }
    }
    return ::operator new (classBytes(size_class), std::align_val_t{kAlignment});
  }
  /// Gives back a block take(inBytes) returned: kept while the cache has room, else freed.
  static void give(void* inBlock, std::size_t inBytes) {
    SAP_ASSERT(serves(inBytes), "a block the cache did not serve");
    const int size_class = classOf(inBytes);
    BufferCache& cache = instance();
    {
      const std::lock_guard<std::mutex> lock(cache.mutex_);
      if (cache.bytes_ + classBytes(size_class) <= kCacheBytes) {
        cache.kept_[size_class].push_back(inBlock);
        cache.bytes_ += classBytes(size_class);
        return;
      }
    }
    ::operator delete (inBlock, std::align_val_t{kAlignment});
  }

 private:
  static constexpr int kClasses = 6;  // blocks of 64 KiB, 128 KiB, ..., 2 MiB

  // A class holds the sizes above half its block and up to its block (the first, 64 KiB
  // exactly: a pair chunk's size).
  static int classOf(std::size_t inBytes) {
    int size_class = 0;
    while ((kSmallestBytes << size_class) < inBytes) ++size_class;
    return size_class;
  }
  static std::size_t classBytes(int inClass) { return kSmallestBytes << inClass; }
  // Never destroyed: buffers of static objects may be given back after exit's destructors ran.
  static BufferCache& instance() {
    static BufferCache* cache = new BufferCache;
    return *cache;
  }

  std::mutex mutex_;
  std::vector<void*> kept_[kClasses];
  std::size_t bytes_ = 0;
};

/// Allocator of the sweep's per-frame buffers, which every frame overwrites in full:
/// - elements are default-initialised, so growing a buffer does not zero it: the first frame's
///   parallel phases are the first to touch its pages, each thread its own slice, instead of
///   one thread zeroing every page before the phase starts;
/// - buffers of a huge page or more are mappings of their own (Linux), aligned to it and
///   advised as huge pages (THP in madvise mode): a first touch faults 2 MiB at a time instead
///   of 4 KiB, the random accesses of the scatters and gathers miss the TLB far less, and a
///   freed buffer leaves the resident set at once (never kept in the heap);
/// - smaller buffers come from the heap, those of 64 KiB and more through BufferCache, so that a
///   fresh engine in a process that ran one before reuses resident pages. Measured on the 2-core VM
///   (2^14 and 2^17 boxes, d = 0.05 and 0.35, alternating in one run): as mappings of their own
///   with their pages populated (MAP_POPULATE, MADV_POPULATE_WRITE), a fresh engine's frame in a
///   warm process cost 1.9 warm plain frames at 2^14 (every fresh engine's buffers were zeroed
///   pages again); from the heap, 1.2; populating heap pages, resident or not, was slower than
///   letting them fault (2^17: 9.0-13.6 against 9.6-16.5 ms) and no faster on a fresh process's
///   first frame;
/// - types aligned beyond what operator new guarantees (a cache-line record) get their
///   alignment.
template <typename T>
struct BufferAllocator {
  using value_type = T;
  static constexpr std::size_t kHugePageBytes = std::size_t{2} << 20;

  BufferAllocator() = default;
  template <typename U>
  BufferAllocator(const BufferAllocator<U>&) {}  // NOLINT: allocators convert implicitly

  T* allocate(std::size_t inCount) {
    const std::size_t bytes = inCount * sizeof(T);
    static_assert(alignof(T) <= BufferCache::kAlignment, "a buffer aligned beyond the cache's");
    if (BufferCache::serves(bytes)) return static_cast<T*>(BufferCache::take(bytes));
    if (bytes < kHugePageBytes) {
      if constexpr (alignof(T) > __STDCPP_DEFAULT_NEW_ALIGNMENT__)
        return static_cast<T*>(::operator new (bytes, std::align_val_t{alignof(T)}));
      else
        return static_cast<T*>(::operator new(bytes));
    }
    const std::size_t rounded = hugeRounded(bytes);
#if defined(__linux__)
    // A mapping of its own rather than the heap: freeing it gives its pages back at once,
    // where glibc, having raised its mmap threshold past the size of a freed block, would
    // serve the next one from the heap and keep it resident after it is freed. Mapped one huge
    // page more than needed, then trimmed to an aligned run.
    void* mapped = mmap(nullptr, rounded + kHugePageBytes, PROT_READ | PROT_WRITE,
                        MAP_PRIVATE | MAP_ANONYMOUS, -1, 0);
    if (mapped == MAP_FAILED) throw std::bad_alloc();
    const auto start = reinterpret_cast<std::uintptr_t>(mapped);
    const std::uintptr_t aligned = (start + kHugePageBytes - 1) / kHugePageBytes * kHugePageBytes;
    if (aligned > start) munmap(mapped, aligned - start);
    if (aligned + rounded < start + rounded + kHugePageBytes)
      munmap(reinterpret_cast<void*>(aligned + rounded),
             start + rounded + kHugePageBytes - aligned - rounded);
    void* memory = reinterpret_cast<void*>(aligned);
#else
    void* memory = std::aligned_alloc(kHugePageBytes, rounded);
    if (!memory) throw std::bad_alloc();
#endif
#if defined(__linux__) && defined(MADV_HUGEPAGE)
    madvise(memory, rounded, MADV_HUGEPAGE);  // advice only: failure leaves small pages
#endif
    return static_cast<T*>(memory);
  }
  void deallocate(T* inMemory, std::size_t inCount) {
    const std::size_t bytes = inCount * sizeof(T);
    if (BufferCache::serves(bytes)) {
      BufferCache::give(inMemory, bytes);
      return;
    }
    if (bytes >= kHugePageBytes) {
#if defined(__linux__)
      munmap(inMemory, hugeRounded(bytes));
#else
      std::free(inMemory);
#endif
    } else if constexpr (alignof(T) > __STDCPP_DEFAULT_NEW_ALIGNMENT__) {
      ::operator delete (inMemory, std::align_val_t{alignof(T)});
    } else {
      ::operator delete(inMemory);
    }
  }
  static std::size_t hugeRounded(std::size_t inBytes) {
    return (inBytes + kHugePageBytes - 1) / kHugePageBytes * kHugePageBytes;
  }
  /// Default-initialises (no zeroing); explicit values are constructed as usual.
  template <typename U, typename... Args>
  void construct(U* inPlace, Args&&... inArgs) {
    if constexpr (sizeof...(Args) == 0)
      ::new (static_cast<void*>(inPlace)) U;
    else
      ::new (static_cast<void*>(inPlace)) U(std::forward<Args>(inArgs)...);
  }
  template <typename U>
  bool operator==(const BufferAllocator<U>&) const {
    return true;
  }
  template <typename U>
  bool operator!=(const BufferAllocator<U>&) const {
    return false;
  }
};

/// A per-frame buffer: a vector whose growth neither zeroes nor touches its memory.
template <typename T>
using Buffer = std::vector<T, BufferAllocator<T>>;

/// Makes ioBuffer hold inSize elements whose old contents do not matter. Growing frees the old
/// storage before allocating the new, so the two are never resident together (a plain resize
/// copies and keeps both for a moment), and leaves an eighth of headroom so that a frame
/// slightly larger than the last does not allocate again.
template <typename T, typename Allocator>
void resizeDiscarding(std::vector<T, Allocator>& ioBuffer, std::size_t inSize) {
  if (inSize > ioBuffer.capacity()) {
    std::vector<T, Allocator>().swap(ioBuffer);
    ioBuffer.reserve(inSize + inSize / 8);
  }
  ioBuffer.resize(inSize);
}

/// True when the two vectors hold the same elements, byte for byte (so -0.0 differs from 0.0).
template <typename T>
bool sameElements(const std::vector<T>& inA, const std::vector<T>& inB) {
  return inA.size() == inB.size() &&
         (inA.empty() || std::memcmp(inA.data(), inB.data(), inA.size() * sizeof(T)) == 0);
}

}  // namespace sap_broadphase
