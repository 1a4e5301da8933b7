// CGAL box_intersection_d on closed boxes: a one-shot algorithm (no state across frames).
// Its documentation leaves one knob to the user, the cutoff below which the streamed
// segment tree falls back to scanning; the default (10) is far from the best on large sets,
// so each cutoff is its own peer and the tables report the best. With TBB, the Parallel_tag
// version runs on two threads as a further peer.
#include <CGAL/box_intersection_d.h>

#ifdef SAP_BENCH_CGAL_PARALLEL
#include <tbb/enumerable_thread_specific.h>
#include <tbb/task_arena.h>
#endif

#include "../bench_stats.h"
#include "peer.h"

namespace sap_bench {
namespace {

using sap_broadphase::BoxSet;
using sap_broadphase::PairList;
using CgalBox = CGAL::Box_intersection_d::Box_with_info_d<double, 3, uint32_t,
                                                          CGAL::Box_intersection_d::ID_EXPLICIT>;

/// CGAL's boxes for inBoxes (timed with the rest: a user converts too); info = the box id.
std::vector<CgalBox> toCgalBoxes(const BoxSet& inBoxes) {
  std::vector<CgalBox> boxes;
  boxes.reserve(inBoxes.size());
  for (std::size_t i = 0; i < inBoxes.size(); ++i) {
    const double lo[3] = {inBoxes.lo(0, i), inBoxes.lo(1, i), inBoxes.lo(2, i)};
    const double hi[3] = {inBoxes.hi(0, i), inBoxes.hi(1, i), inBoxes.hi(2, i)};
    boxes.emplace_back(CGAL::Bbox_3(lo[0], lo[1], lo[2], hi[0], hi[1], hi[2]), inBoxes.ids[i]);
  }
  return boxes;
}

class CgalPeer : public Peer {
 public:
  explicit CgalPeer(std::ptrdiff_t inCutoff) : cutoff_(inCutoff) {}
  std::string name() const override { return "cgal_c" + std::to_string(cutoff_); }
  std::string family() const override { return "cgal"; }
  std::string semantics() const override { return "exact, closed boxes (CLOSED topology)"; }

  PeerResult oneShot(const BoxSet& inBoxes) override {
    Stopwatch clock;
    std::vector<CgalBox> boxes = toCgalBoxes(inBoxes);
    PeerResult result;
    CGAL::box_self_intersection_d(
        boxes.begin(), boxes.end(),
        [&result](const CgalBox& inA, const CgalBox& inB) {
          result.pairs.push_back(sap_broadphase::makeIdPair(inA.info(), inB.info()));
        },
        cutoff_, CGAL::Box_intersection_d::CLOSED);
    result.ms = clock.ms();
    return result;
  }

 private:
  std::ptrdiff_t cutoff_;
};

#ifdef SAP_BENCH_CGAL_PARALLEL
/// The TBB version in an arena of inThreads threads; each thread collects into its own list.
class CgalParallelPeer : public Peer {
 public:
  CgalParallelPeer(std::ptrdiff_t inCutoff, int inThreads)
      : cutoff_(inCutoff), threads_(inThreads), arena_(inThreads) {}
  std::string name() const override {
    return "cgal_tbb_t" + std::to_string(threads_) + "_c" + std::to_string(cutoff_);
  }
  std::string family() const override { return "cgal_tbb"; }
  std::string semantics() const override { return "exact, closed boxes (CLOSED topology)"; }

  PeerResult oneShot(const BoxSet& inBoxes) override {
    Stopwatch clock;
    std::vector<CgalBox> boxes = toCgalBoxes(inBoxes);
    tbb::enumerable_thread_specific<PairList> perThread;
    arena_.execute([&] {
      CGAL::box_self_intersection_d<CGAL::Parallel_tag>(
          boxes.begin(), boxes.end(),
          [&perThread](const CgalBox& inA, const CgalBox& inB) {
            perThread.local().push_back(sap_broadphase::makeIdPair(inA.info(), inB.info()));
          },
          cutoff_, CGAL::Box_intersection_d::CLOSED);
    });
    PeerResult result;
    for (const PairList& part : perThread)
      result.pairs.insert(result.pairs.end(), part.begin(), part.end());
    result.ms = clock.ms();
    return result;
  }

 private:
  std::ptrdiff_t cutoff_;
  int threads_;
  tbb::task_arena arena_;
};
#endif

}  // namespace

void addCgalPeers(Peers& ioPeers) {
  for (std::ptrdiff_t cutoff : {10, 100, 300, 1000, 3000})
    ioPeers.push_back(std::make_unique<CgalPeer>(cutoff));
#ifdef SAP_BENCH_CGAL_PARALLEL
  for (std::ptrdiff_t cutoff : {300, 1000, 3000})
    ioPeers.push_back(std::make_unique<CgalParallelPeer>(cutoff, 2));
#endif
}

}  // namespace sap_bench
