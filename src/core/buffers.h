// Buffers that every frame overwrites.
#pragma once

#include <cstddef>
#include <cstring>
#include <vector>

namespace sap_broadphase {

/// Makes ioBuffer hold inSize elements whose old contents do not matter. Growing frees the old
/// storage before allocating the new, so the two are never resident together (a plain resize
/// copies and keeps both for a moment), and leaves an eighth of headroom so that a frame
/// slightly larger than the last does not allocate again.
template <typename T>
void resizeDiscarding(std::vector<T>& ioBuffer, std::size_t inSize) {
  if (inSize > ioBuffer.capacity()) {
    std::vector<T>().swap(ioBuffer);
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
