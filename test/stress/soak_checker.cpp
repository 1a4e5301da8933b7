// Soak and huge-frame client of the node (scripts/soak.sh). ROS 1 node, no roscore of its own.
//
//   soak_checker soak  SECONDS SAMPLE_PERIOD_S   topic frames sampled by stamp and checked
//                                                against an independent sweep oracle, while a
//                                                second thread calls compute_pairs in a loop
//   soak_checker huge  BOXES                     one frame of BOXES uniform boxes through the
//                                                topic and the service, both checked
//
// Prints one summary line per check and "soak_checker: PASS" or "soak_checker: FAIL".
#include <ros/ros.h>

#include <algorithm>
#include <atomic>
#include <chrono>
#include <cstdio>
#include <cstdlib>
#include <map>
#include <memory>
#include <mutex>
#include <numeric>
#include <string>
#include <thread>
#include <vector>

#include <cmath>
#include <cstdint>
#include <utility>

#include "sap_broadphase/BoxArray.h"
#include "sap_broadphase/ComputePairs.h"
#include "sap_broadphase/PairArray.h"

// Only the generated messages and the project's header-only random generator (by a path
// relative to this file, so soak.sh needs no engine include path): the checker shares no code
// with the engine it checks.
#include "../../src/core/tools/random.h"

namespace sap_broadphase {
namespace {

using Clock = std::chrono::steady_clock;
using IdPair = std::pair<uint32_t, uint32_t>;
using PairList = std::vector<IdPair>;
constexpr uint32_t kDefaultGroup = 0x1u;
constexpr uint32_t kDefaultMask = 0xFFFFFFFFu;

IdPair makeIdPair(uint32_t inX, uint32_t inY) {
  return inX < inY ? IdPair{inX, inY} : IdPair{inY, inX};
}

/// inCount boxes with edges in [0.5, 1.5), uniform in a cube sized for 5 % density (the
/// uniform scene's default), ids empty (0..n-1) as scene_publisher sends them.
BoxArray uniformFrame(std::size_t inCount, uint64_t inSeed) {
  SplitMix64 random(inSeed);
  const double side = std::cbrt(static_cast<double>(inCount) / 0.05);
  BoxArray msg;
  msg.bounds.resize(6 * inCount);
  for (std::size_t i = 0; i < inCount; ++i) {
    for (int axis = 0; axis < 3; ++axis) {
      const double low = random.unit() * side;
      msg.bounds[6 * i + axis] = low;
      msg.bounds[6 * i + 3 + axis] = low + 0.5 + random.unit();
    }
  }
  return msg;
}

/// All overlapping pairs of a message's boxes, closed intervals, filters honoured, by a
/// uniform grid: cells a little wider than the largest box edge, each box filed under the cell
/// of its min corner; two boxes that overlap have min corners in the same or adjacent cells.
/// Independent of the engine; O(n) for the uniform scene (2^21 boxes in seconds). Frames with
/// infinite or widely spread coordinates fall back to a sweep on x.
std::vector<uint32_t> sweepOracle(const BoxArray& inMsg) {
  const std::size_t n = inMsg.bounds.size() / 6;
  const double* b = inMsg.bounds.data();
  auto id = [&](std::size_t i) { return inMsg.ids.empty() ? uint32_t(i) : inMsg.ids[i]; };
  auto group = [&](std::size_t i) {
    return inMsg.groups.empty() ? kDefaultGroup : inMsg.groups[i];
  };
  auto mask = [&](std::size_t i) { return inMsg.masks.empty() ? kDefaultMask : inMsg.masks[i]; };
  auto overlap = [&](std::size_t i, std::size_t j) {
    for (int a = 0; a < 3; ++a)
      if (b[6 * i + a] > b[6 * j + 3 + a] || b[6 * j + a] > b[6 * i + 3 + a]) return false;
    return (group(i) & mask(j)) != 0 && (group(j) & mask(i)) != 0;
  };
  double origin[3] = {INFINITY, INFINITY, INFINITY};
  double top[3] = {-INFINITY, -INFINITY, -INFINITY};
  double edge = 0.0;
  for (std::size_t i = 0; i < n; ++i)
    for (int a = 0; a < 3; ++a) {
      origin[a] = std::min(origin[a], b[6 * i + a]);
      top[a] = std::max(top[a], b[6 * i + a]);
      edge = std::max(edge, b[6 * i + 3 + a] - b[6 * i + a]);
    }
  // Any cell at least as wide as the largest edge is exact; wider cells bound the grid size.
  double span = 0.0;
  for (int a = 0; a < 3 && n > 0; ++a) span = std::max(span, top[a] - origin[a]);
  const double cell = std::max({edge * (1.0 + 1e-9), span / 400.0, 1e-300});
  std::size_t dims[3] = {1, 1, 1};
  double cells = 1.0;
  for (int a = 0; a < 3 && n > 0; ++a) {
    const double count = std::floor((top[a] - origin[a]) / cell) + 1.0;
    cells *= count;
    dims[a] = std::isfinite(count) ? static_cast<std::size_t>(std::min(count, 1e9)) : 0;
  }
  PairList pairs;
  if (n > 0 && std::isfinite(cells) && cells <= 70e6 && dims[0] * dims[1] * dims[2] > 0) {
    auto coordinate = [&](std::size_t i, int a) {
      return std::min(dims[a] - 1, static_cast<std::size_t>((b[6 * i + a] - origin[a]) / cell));
    };
    std::vector<uint32_t> start(dims[0] * dims[1] * dims[2] + 1, 0);
    std::vector<std::size_t> cell_of(n);
    for (std::size_t i = 0; i < n; ++i) {
      cell_of[i] = (coordinate(i, 0) * dims[1] + coordinate(i, 1)) * dims[2] + coordinate(i, 2);
      ++start[cell_of[i] + 1];
    }
    for (std::size_t c = 1; c < start.size(); ++c) start[c] += start[c - 1];
    std::vector<uint32_t> members(n);
    std::vector<uint32_t> fill(start.begin(), start.end() - 1);
    for (std::size_t i = 0; i < n; ++i) members[fill[cell_of[i]]++] = static_cast<uint32_t>(i);
    for (std::size_t i = 0; i < n; ++i) {
      const std::size_t home[3] = {coordinate(i, 0), coordinate(i, 1), coordinate(i, 2)};
      for (std::size_t x = home[0] ? home[0] - 1 : 0; x <= std::min(dims[0] - 1, home[0] + 1); ++x)
        for (std::size_t y = home[1] ? home[1] - 1 : 0; y <= std::min(dims[1] - 1, home[1] + 1);
             ++y)
          for (std::size_t z = home[2] ? home[2] - 1 : 0; z <= std::min(dims[2] - 1, home[2] + 1);
               ++z) {
            const std::size_t c = (x * dims[1] + y) * dims[2] + z;
            for (uint32_t k = start[c]; k < start[c + 1]; ++k)
              if (members[k] > i && overlap(i, members[k]))
                pairs.push_back(makeIdPair(id(i), id(members[k])));
          }
    }
  } else {
    std::vector<uint32_t> order(n);
    std::iota(order.begin(), order.end(), 0u);
    std::sort(order.begin(), order.end(),
              [&](uint32_t x, uint32_t y) { return b[6 * x] < b[6 * y]; });
    for (std::size_t k = 0; k < n; ++k)
      for (std::size_t m = k + 1; m < n && b[6 * order[m]] <= b[6 * order[k] + 3]; ++m)
        if (overlap(order[k], order[m])) pairs.push_back(makeIdPair(id(order[k]), id(order[m])));
  }
  std::sort(pairs.begin(), pairs.end());
  std::vector<uint32_t> flat;
  flat.reserve(2 * pairs.size());
  for (const IdPair& pair : pairs) {
    flat.push_back(pair.first);
    flat.push_back(pair.second);
  }
  return flat;
}

/// Sampled topic frames waiting for their pairs, keyed by stamp.
class FrameSampler {
 public:
  explicit FrameSampler(double inPeriod) : period_(inPeriod) {}

  void onBoxes(const BoxArrayConstPtr& inMsg) {
    std::lock_guard<std::mutex> lock(mutex_);
    ++boxes_seen_;
    latest_ = inMsg;
    // Every frame waits for its pairs; the node drops most under load, so only the newest
    // few are kept (messages are shared, not copied).
    waiting_[inMsg->header.stamp] = inMsg;
    while (waiting_.size() > 16) waiting_.erase(waiting_.begin());
  }

  void onPairs(const PairArrayConstPtr& inMsg) {
    BoxArrayConstPtr frame;
    {
      std::lock_guard<std::mutex> lock(mutex_);
      ++pairs_seen_;
      const auto found = waiting_.find(inMsg->header.stamp);
      if (found == waiting_.end()) return;
      frame = found->second;
      waiting_.erase(found);
      ++matched_;
      // The oracle costs CPU the node needs: check at most one frame per period.
      const double now = ros::WallTime::now().toSec();
      if (now - last_check_ < period_) return;
      last_check_ = now;
    }
    const bool exact = sweepOracle(*frame) == inMsg->pairs;
    std::lock_guard<std::mutex> lock(mutex_);
    ++checked_;
    if (!exact) {
      ++mismatched_;
      std::printf("soak_checker: MISMATCH topic frame stamp %u.%09u: %zu pairs published\n",
                  inMsg->header.stamp.sec, inMsg->header.stamp.nsec, inMsg->pairs.size() / 2);
    }
  }

  BoxArrayConstPtr latest() {
    std::lock_guard<std::mutex> lock(mutex_);
    return latest_;
  }

  double period_;
  std::mutex mutex_;
  double last_check_ = 0.0;
  std::map<ros::Time, BoxArrayConstPtr> waiting_;
  BoxArrayConstPtr latest_;
  uint64_t boxes_seen_ = 0, pairs_seen_ = 0, matched_ = 0, checked_ = 0, mismatched_ = 0;
};

struct ServiceTally {
  std::atomic<uint64_t> calls{0}, exact{0}, wrong{0}, failed{0};
};

// Calls compute_pairs with the latest topic frame until inStop, checking each answer.
void serviceLoop(ros::NodeHandle& ioNode, FrameSampler& ioSampler, const std::atomic<bool>& inStop,
                 ServiceTally& outTally) {
  ros::ServiceClient client = ioNode.serviceClient<ComputePairs>("compute_pairs", true);
  while (!inStop && ros::ok()) {
    BoxArrayConstPtr frame = ioSampler.latest();
    if (!frame || !client.isValid()) {
      if (!client.isValid()) client = ioNode.serviceClient<ComputePairs>("compute_pairs", true);
      std::this_thread::sleep_for(std::chrono::milliseconds(50));
      continue;
    }
    ComputePairs call;
    call.request.boxes = *frame;
    ++outTally.calls;
    if (!client.call(call) || !call.response.success) {
      ++outTally.failed;
      continue;
    }
    if (sweepOracle(*frame) == call.response.pairs.pairs)
      ++outTally.exact;
    else
      ++outTally.wrong;
  }
}

int soak(double inSeconds, double inSamplePeriod) {
  ros::NodeHandle node;
  FrameSampler sampler(inSamplePeriod);
  ros::Subscriber boxes_sub = node.subscribe("boxes", 1, &FrameSampler::onBoxes, &sampler,
                                             ros::TransportHints().tcpNoDelay());
  ros::Subscriber pairs_sub = node.subscribe("pairs", 10, &FrameSampler::onPairs, &sampler,
                                             ros::TransportHints().tcpNoDelay());
  ros::AsyncSpinner spinner(2);
  spinner.start();
  std::atomic<bool> stop{false};
  ServiceTally tally;
  ros::service::waitForService("compute_pairs", ros::Duration(30));
  std::thread caller(serviceLoop, std::ref(node), std::ref(sampler), std::cref(stop),
                     std::ref(tally));
  const auto end = Clock::now() + std::chrono::duration<double>(inSeconds);
  while (Clock::now() < end && ros::ok())
    std::this_thread::sleep_for(std::chrono::milliseconds(200));
  stop = true;
  caller.join();
  spinner.stop();
  std::lock_guard<std::mutex> lock(sampler.mutex_);
  std::printf(
      "soak_checker: topic: %llu boxes frames seen, %llu pairs frames seen (%llu matched to "
      "their boxes by stamp), %llu of those checked against the oracle, %llu mismatches\n",
      static_cast<unsigned long long>(sampler.boxes_seen_),
      static_cast<unsigned long long>(sampler.pairs_seen_),
      static_cast<unsigned long long>(sampler.matched_),
      static_cast<unsigned long long>(sampler.checked_),
      static_cast<unsigned long long>(sampler.mismatched_));
  std::printf("soak_checker: service: %llu calls, %llu exact, %llu wrong, %llu failed\n",
              static_cast<unsigned long long>(tally.calls.load()),
              static_cast<unsigned long long>(tally.exact.load()),
              static_cast<unsigned long long>(tally.wrong.load()),
              static_cast<unsigned long long>(tally.failed.load()));
  const bool pass =
      sampler.checked_ > 0 && sampler.mismatched_ == 0 && tally.wrong == 0 && tally.exact > 0;
  std::printf("soak_checker: %s\n", pass ? "PASS" : "FAIL");
  return pass ? 0 : 1;
}

int huge(std::size_t inBoxes) {
  ros::NodeHandle node;
  const auto build_start = Clock::now();
  BoxArray msg = uniformFrame(inBoxes, 7);
  msg.header.frame_id = "map";
  msg.header.stamp = ros::Time::now();
  const std_msgs::Header header = msg.header;
  const std::size_t bytes = ros::serialization::serializationLength(msg);
  std::printf("soak_checker: huge frame of %zu boxes, %.1f MB serialized (built in %.1f s)\n",
              inBoxes, bytes / 1e6,
              std::chrono::duration<double>(Clock::now() - build_start).count());
  std::vector<uint32_t> expected;
  bool got_pairs = false;
  std::vector<uint32_t> topic_pairs;
  std::mutex mutex;
  ros::Subscriber pairs_sub =
      node.subscribe<PairArray>("pairs", 2, [&](const PairArrayConstPtr& inPairs) {
        std::lock_guard<std::mutex> lock(mutex);
        if (inPairs->header.stamp != header.stamp) return;
        topic_pairs = inPairs->pairs;
        got_pairs = true;
      });
  ros::Publisher boxes_pub = node.advertise<BoxArray>("boxes", 1);
  ros::AsyncSpinner spinner(1);
  spinner.start();
  for (int k = 0;
       k < 100 && (boxes_pub.getNumSubscribers() == 0 || pairs_sub.getNumPublishers() == 0); ++k)
    std::this_thread::sleep_for(std::chrono::milliseconds(100));
  const auto topic_start = Clock::now();
  boxes_pub.publish(msg);
  const auto oracle_start = Clock::now();
  expected = sweepOracle(msg);
  std::printf("soak_checker: oracle: %zu pairs in %.1f s\n", expected.size() / 2,
              std::chrono::duration<double>(Clock::now() - oracle_start).count());
  bool topic_ok = false;
  for (int k = 0; k < 1200 && ros::ok(); ++k) {
    {
      std::lock_guard<std::mutex> lock(mutex);
      if (got_pairs) break;
    }
    std::this_thread::sleep_for(std::chrono::milliseconds(100));
  }
  {
    std::lock_guard<std::mutex> lock(mutex);
    topic_ok = got_pairs && topic_pairs == expected;
    std::printf("soak_checker: topic: %s after %.1f s (%zu pairs)\n",
                got_pairs ? (topic_ok ? "exact pairs" : "WRONG pairs") : "no pairs within 120 s",
                std::chrono::duration<double>(Clock::now() - topic_start).count(),
                topic_pairs.size() / 2);
  }
  ComputePairs call;
  call.request.boxes = msg;
  const auto service_start = Clock::now();
  const bool called = ros::service::call("compute_pairs", call);
  const bool service_ok = called && call.response.success && call.response.pairs.pairs == expected;
  std::printf("soak_checker: service: %s after %.1f s (success %d, %zu pairs, message '%s')\n",
              !called ? "call FAILED" : (service_ok ? "exact pairs" : "not exact"),
              std::chrono::duration<double>(Clock::now() - service_start).count(),
              static_cast<int>(call.response.success), call.response.pairs.pairs.size() / 2,
              call.response.message.c_str());
  std::printf("soak_checker: %s\n", topic_ok && service_ok ? "PASS" : "FAIL");
  return topic_ok && service_ok ? 0 : 1;
}

// The grid oracle against all pairs tested, on a few small frames (also with filters and ids).
int selfTest() {
  for (std::size_t n : {0, 1, 500, 3000}) {
    BoxArray msg = uniformFrame(n, n + 1);
    if (n == 500) {
      for (std::size_t i = 0; i < n; ++i) {
        msg.ids.push_back(static_cast<uint32_t>(4000000000u - 7 * i));
        msg.groups.push_back(1u + i % 3);
        msg.masks.push_back(i % 5 ? 0xFFFFFFFFu : 2u);
      }
    }
    PairList all;
    for (std::size_t i = 0; i < n; ++i)
      for (std::size_t j = i + 1; j < n; ++j) {
        bool hit = true;
        for (int a = 0; a < 3; ++a)
          hit = hit && msg.bounds[6 * i + a] <= msg.bounds[6 * j + 3 + a] &&
                msg.bounds[6 * j + a] <= msg.bounds[6 * i + 3 + a];
        const uint32_t gi = msg.groups.empty() ? kDefaultGroup : msg.groups[i];
        const uint32_t gj = msg.groups.empty() ? kDefaultGroup : msg.groups[j];
        const uint32_t mi = msg.masks.empty() ? kDefaultMask : msg.masks[i];
        const uint32_t mj = msg.masks.empty() ? kDefaultMask : msg.masks[j];
        if (hit && (gi & mj) && (gj & mi))
          all.push_back(makeIdPair(msg.ids.empty() ? uint32_t(i) : msg.ids[i],
                                   msg.ids.empty() ? uint32_t(j) : msg.ids[j]));
      }
    std::sort(all.begin(), all.end());
    std::vector<uint32_t> flat;
    for (const IdPair& pair : all) {
      flat.push_back(pair.first);
      flat.push_back(pair.second);
    }
    if (sweepOracle(msg) != flat) {
      std::printf("soak_checker: selftest FAILED at n = %zu\n", n);
      return 1;
    }
  }
  std::printf("soak_checker: selftest passed (grid oracle = all pairs tested)\n");
  return 0;
}

}  // namespace
}  // namespace sap_broadphase

int main(int argc, char** argv) {
  ros::init(argc, argv, "soak_checker", ros::init_options::AnonymousName);
  std::setvbuf(stdout, nullptr, _IOLBF, 0);  // lines reach `tee` as they are printed
  const std::string mode = argc > 1 ? argv[1] : "";
  if (mode == "selftest") return sap_broadphase::selfTest();
  if (mode == "soak" && argc == 4)
    return sap_broadphase::soak(std::atof(argv[2]), std::atof(argv[3]));
  if (mode == "huge" && argc == 3) return sap_broadphase::huge(std::strtoull(argv[2], nullptr, 10));
  std::fprintf(stderr, "usage: soak_checker soak SECONDS SAMPLE_PERIOD | huge BOXES\n");
  return 2;
}
