// The per-frame pipeline: keys -> parallel radix sort -> candidates -> pairing -> sorted pairs.
#pragma once

#include <cstddef>
#include <cstdint>
#include <memory>
#include <optional>
#include <string>

#include "sap_broadphase/core/box_set.h"
#include "sap_broadphase/core/config.h"
#include "sap_broadphase/core/frame_report.h"
#include "sap_broadphase/core/pair_set.h"

namespace sap_broadphase {

/// The stateful broad phase: keeps partition bounds B and the sweep axes across frames, owns
/// every buffer (no allocation per frame once sizes are stable). Not thread-safe: one frame at
/// a time per instance. The input is trusted: validate() it at the edge first.
class Broadphase {
 public:
  explicit Broadphase(const BroadphaseConfig& inConfig = BroadphaseConfig());
  ~Broadphase();
  Broadphase(Broadphase&&) noexcept;
  Broadphase& operator=(Broadphase&&) noexcept;

  /// Computes every overlapping pair of inBoxes (closed intervals, filters honoured), as ids
  /// with a < b in canonical (a, b) order. The reference stays valid until the next update().
  const PairList& update(const BoxSet& inBoxes);
  /// The same for boxes laid out as records (a BoxArray message's bounds), which the engine
  /// checks itself as it reads them: the engine keeps a copy of every frame anyway (to know
  /// what moved), and here that copy is made from inBoxes directly, checked on the way, so the
  /// caller's memory is read once and no intermediate BoxSet is built. Throws InvalidBoxes
  /// naming the lowest bad box as validate() does (NaN, min > max, a repeated id, too many
  /// boxes); the engine is then as after reset(). inBoxes is read only during the call.
  const PairList& update(const InterleavedBoxes& inBoxes);
  /// Declares scenery: boxes that stay put until replaced (validate() them first). They are
  /// indexed once, here; every later update() reports the pairs among its boxes and between
  /// its boxes and the scenery, never scenery x scenery pairs (as the static bodies of Box2D,
  /// Jolt and Bullet). Ids of update()'s boxes must differ from the scenery's ids. Replaces
  /// any earlier scenery.
  void setStaticBoxes(const BoxSet& inStaticBoxes);
  /// Forgets the scenery.
  void clearStaticBoxes();
  /// Number of declared static boxes.
  std::size_t staticBoxCount() const;
  /// Statistics of the last update().
  const FrameReport& stats() const;
  /// The configuration in force (axes change when swapped).
  const BroadphaseConfig& config() const;
  /// Forgets temporal state (partition bounds); the next frame starts as a first frame.
  void reset();

 private:
  struct Impl;
  std::unique_ptr<Impl> impl_;
};

}  // namespace sap_broadphase
