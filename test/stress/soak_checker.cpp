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

// Only the generated messages: the checker shares no code with the engine it checks.
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
  uint64_t state = inSeed;
  auto unit = [&state]() {
    uint64_t z = (state += 0x9E3779B97F4A7C15ull);
    z = (z ^ (z >> 30)) * 0xBF58476D1CE4E5B9ull;
    z = (z ^ (z >> 27)) * 0x94D049BB133111EBull;
    return static_cast<double>((z ^ (z >> 31)) >> 11) * 0x1.0p-53;
  };
  const double side = std::cbrt(static_cast<double>(inCount) / 0.05);
  BoxArray msg;
  msg.bounds.resize(6 * inCount);
  for (std::size_t i = 0; i < inCount; ++i) {
    for (int axis = 0; axis < 3; ++axis) {
      const double low = unit() * side;
      msg.bounds[6 * i + axis] = low;
      msg.bounds[6 * i + 3 + axis] = low + 0.5 + unit();
    }
  }
  return msg;
}

/// All overlapping pairs of a message's boxes by a plain sweep on x (sorted by min x, scan
/// while min x <= max x of the box), closed intervals, filters honoured: independent of the
/// engine and O(n log n + candidates), fast enough for 2^21 uniform boxes.
std::vector<uint32_t> sweepOracle(const BoxArray& inMsg) {
  const std::size_t n = inMsg.bounds.size() / 6;
  const double* b = inMsg.bounds.data();
  std::vector<uint32_t> order(n);
  std::iota(order.begin(), order.end(), 0u);
  std::sort(order.begin(), order.end(),
            [&](uint32_t x, uint32_t y) { return b[6 * x] < b[6 * y]; });
  auto id = [&](uint32_t i) { return inMsg.ids.empty() ? i : inMsg.ids[i]; };
  auto group = [&](uint32_t i) { return inMsg.groups.empty() ? kDefaultGroup : inMsg.groups[i]; };
  auto mask = [&](uint32_t i) { return inMsg.masks.empty() ? kDefaultMask : inMsg.masks[i]; };
  PairList pairs;
  for (std::size_t k = 0; k < n; ++k) {
    const uint32_t i = order[k];
    for (std::size_t m = k + 1; m < n && b[6 * order[m]] <= b[6 * i + 3]; ++m) {
      const uint32_t j = order[m];
      if (b[6 * i + 1] > b[6 * j + 4] || b[6 * j + 1] > b[6 * i + 4]) continue;
      if (b[6 * i + 2] > b[6 * j + 5] || b[6 * j + 2] > b[6 * i + 5]) continue;
      if ((group(i) & mask(j)) == 0 || (group(j) & mask(i)) == 0) continue;
      pairs.push_back(makeIdPair(id(i), id(j)));
    }
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
    const double now = ros::WallTime::now().toSec();
    if (now - last_sample_ < period_) return;
    last_sample_ = now;
    waiting_[inMsg->header.stamp] = inMsg;
    // Frames the node dropped never get pairs: forget them after a while.
    while (waiting_.size() > 8) waiting_.erase(waiting_.begin());
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
  double last_sample_ = 0.0;
  std::map<ros::Time, BoxArrayConstPtr> waiting_;
  BoxArrayConstPtr latest_;
  uint64_t boxes_seen_ = 0, pairs_seen_ = 0, checked_ = 0, mismatched_ = 0;
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
      "soak_checker: topic: %llu boxes frames seen, %llu pairs frames seen, %llu sampled "
      "frames checked exactly, %llu mismatches\n",
      static_cast<unsigned long long>(sampler.boxes_seen_),
      static_cast<unsigned long long>(sampler.pairs_seen_),
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

}  // namespace
}  // namespace sap_broadphase

int main(int argc, char** argv) {
  ros::init(argc, argv, "soak_checker", ros::init_options::AnonymousName);
  const std::string mode = argc > 1 ? argv[1] : "";
  if (mode == "soak" && argc == 4)
    return sap_broadphase::soak(std::atof(argv[2]), std::atof(argv[3]));
  if (mode == "huge" && argc == 3) return sap_broadphase::huge(std::strtoull(argv[2], nullptr, 10));
  std::fprintf(stderr, "usage: soak_checker soak SECONDS SAMPLE_PERIOD | huge BOXES\n");
  return 2;
}
