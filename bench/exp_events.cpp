// Contact events (Broadphase::events()): what finding the began and ended pairs costs in a
// steady frame, against the frame itself and against what a caller of update() did before
// (two std::set_difference of the last and the current list and a copy of the current one, as
// the node's pair_events did). Uniform scenes moving at 1 % of a box a frame, d = 0.05 and
// 0.35, at 2^17 and 2^20 boxes, on the engine's default configuration. The engine's events are
// timed as it finds them, one merge of the two sorted lists (core/contact_events.h), on the
// frame's own lists; every frame's events are checked against the set differences.
#include <algorithm>
#include <iterator>
#include <string>
#include <vector>

#include "bench_output.h"
#include "bench_scenes.h"
#include "bench_stats.h"
#include "core/frame/contact_events.h"
#include "experiments.h"
#include "sap_broadphase/core/broadphase.h"
#include "sap_broadphase/core/scenes.h"

namespace sap_bench {
namespace {

using sap_broadphase::BoxSet;
using sap_broadphase::Broadphase;
using sap_broadphase::BroadphaseConfig;
using sap_broadphase::ContactEvents;
using sap_broadphase::PairList;

constexpr double kSpeed = 0.01;
constexpr double kDensities[] = {0.05, 0.35};
constexpr double kTargetShare = 0.10;  // events at most 10 % of a steady frame

/// The per-frame measurements of one scene (steady frames only).
struct EventsSamples {
  std::vector<double> frame_ms, merge_ms, set_difference_ms, pairs, changed;
  bool events_match = true;
};

/// The caller's way before events(): the two differences into new lists, then a copy of the
/// current list kept for the next frame.
void differencesAndCopy(const PairList& inNow, PairList& ioPrevious, ContactEvents& outEvents) {
  PairList began, ended;
  std::set_difference(inNow.begin(), inNow.end(), ioPrevious.begin(), ioPrevious.end(),
                      std::back_inserter(began));
  std::set_difference(ioPrevious.begin(), ioPrevious.end(), inNow.begin(), inNow.end(),
                      std::back_inserter(ended));
  ioPrevious.assign(inNow.begin(), inNow.end());
  outEvents.began.swap(began);
  outEvents.ended.swap(ended);
}

EventsSamples runScene(std::size_t inCount, double inDensity, int inFrames,
                       const Options& inOptions) {
  sap_broadphase::SceneConfig scene = uniformScene(inCount, inDensity, inOptions.seed);
  scene.speed = kSpeed;
  FrameFeed feed(scene, 0);
  BroadphaseConfig config;
  config.threads = inOptions.threads;
  Broadphase engine(config);
  EventsSamples samples;
  PairList last, now, previous_copy;
  ContactEvents merged, differenced;
  for (int f = 0; f <= inFrames; ++f) {
    if (f > 0) feed.step();
    Stopwatch frame;
    const PairList& pairs = engine.update(feed.boxes());
    const double frame_ms = frame.ms();
    now.assign(pairs.begin(), pairs.end());
    Stopwatch merge;
    sap_broadphase::diffPairLists(last, now, merged);
    const double merge_ms = merge.ms();
    Stopwatch differences;
    differencesAndCopy(now, previous_copy, differenced);
    const double set_difference_ms = differences.ms();
    const ContactEvents& events = engine.events();
    samples.events_match = samples.events_match && events.began == differenced.began &&
                           events.ended == differenced.ended && merged.began == events.began &&
                           merged.ended == events.ended;
    if (f > 0) {  // the first frame: every pair begins, no steady frame
      samples.frame_ms.push_back(frame_ms);
      samples.merge_ms.push_back(merge_ms);
      samples.set_difference_ms.push_back(set_difference_ms);
      samples.pairs.push_back(static_cast<double>(now.size()));
      samples.changed.push_back(static_cast<double>(events.began.size() + events.ended.size()));
    }
    last.swap(now);
  }
  return samples;
}

}  // namespace

void runEvents(const Options& inOptions) {
  const std::vector<std::size_t> sizes = inOptions.sizes(
      {std::size_t{1} << 17, std::size_t{1} << 20}, {std::size_t{1} << 12, std::size_t{1} << 14});
  const int frames = inOptions.framesOr(20, 4);
  Table table("Contact events in a steady frame (uniform, 1 % motion): ms, median of " +
                  std::to_string(frames) + " frames",
              {"n", "density", "pairs", "began_plus_ended", "frame_ms", "events_merge_ms",
               "set_difference_copy_ms", "events_pct_of_frame", "merge_over_set_difference",
               "target_10pct", "check"});
  Panel share("Events against the frame", "boxes", "ms per steady frame", true, true);
  for (double density : kDensities) {
    Series frame_series, merge_series, difference_series;
    frame_series.title = "frame, d=" + fmt(density, 2);
    merge_series.title = "events (merge), d=" + fmt(density, 2);
    difference_series.title = "2 set_difference + copy, d=" + fmt(density, 2);
    for (std::size_t n : sizes) {
      const EventsSamples samples = runScene(n, density, frames, inOptions);
      const double frame_ms = median(samples.frame_ms);
      const double merge_ms = median(samples.merge_ms);
      const double difference_ms = median(samples.set_difference_ms);
      const double share_of_frame = frame_ms > 0.0 ? merge_ms / frame_ms : 0.0;
      table.addRow(
          {fmtSize(n), fmt(density, 2), fmtCount(static_cast<std::size_t>(median(samples.pairs))),
           fmtCount(static_cast<std::size_t>(median(samples.changed))), fmt(frame_ms),
           fmt(merge_ms), fmt(difference_ms), fmt(100.0 * share_of_frame, 3),
           fmtRatio(difference_ms, merge_ms), share_of_frame <= kTargetShare ? "met" : "missed",
           samples.events_match ? "ok" : "MISMATCH"});
      frame_series.add(static_cast<double>(n), frame_ms);
      merge_series.add(static_cast<double>(n), merge_ms);
      difference_series.add(static_cast<double>(n), difference_ms);
    }
    share.series.push_back(frame_series);
    share.series.push_back(merge_series);
    share.series.push_back(difference_series);
  }
  publish(inOptions, table, "events", {Figure{"events", {share}}});
}

}  // namespace sap_bench
