// sap_ros_latency: end-to-end latency through ROS. Publishes uniform-scene
// frames as BoxArray on `boxes`, waits for the node's PairArray on `pairs` and FrameStats on
// `stats` (matched by header.stamp), and splits the publish -> pairs-received latency into the
// part spent in the engine's sweep and the part spent outside it (serialisation, transport,
// deserialisation, conversion, output).
//
// Two transports, measured side by side in one run on the same frames:
//   tcp      the node is another process (started beside this one, e.g. by bench_ros.sh): every
//            BoxArray and PairArray is serialised, sent over loopback TCP and deserialised;
//   nodelet  sap_broadphase/BroadphaseNodelet is loaded into this process (a nodelet::Loader,
//            namespace in_process), so publisher, node and this measuring subscriber share one
//            process and the frames pass as shared pointers, never serialised.
//
// Two modes per configuration:
//   latency     one frame in flight: the next frame is published only after the previous
//               frame's pairs and stats arrived (nothing can be dropped);
//   throughput  two frames in flight: frame k+2 is published when frame k's pairs arrive, so
//               the transport of one frame overlaps the processing of the previous one.
// Frames are generated (SceneSimulator, fixed seed) and converted to messages before timing
// starts; ids are left empty as scene_publisher does (boxes numbered 0..n-1).
//
// Times: steady_clock in this process (publish() call -> pairs callback entered, which includes
// deserialising the PairArray), plus the node's FrameStats of the same frame. Medians are per
// column over the measured frames (warm-up frames excluded), so they need not add up exactly.
#include <algorithm>
#include <chrono>
#include <cmath>
#include <condition_variable>
#include <cstdint>
#include <cstdio>
#include <cstdlib>
#include <fstream>
#include <iostream>
#include <map>
#include <memory>
#include <mutex>
#include <optional>
#include <sstream>
#include <string>
#include <vector>

#include <nodelet/loader.h>
#include <ros/ros.h>
#include <ros/serialization.h>
#include <boost/make_shared.hpp>

#include "sap_broadphase/BoxArray.h"
#include "sap_broadphase/FrameStats.h"
#include "sap_broadphase/PairArray.h"
#include "sap_broadphase/core/scenes.h"
#include "sap_broadphase/ros/conversions.h"

namespace {

using Clock = std::chrono::steady_clock;
using sap_broadphase::BoxArray;
using sap_broadphase::BoxArrayPtr;
using sap_broadphase::FrameStats;
using sap_broadphase::PairArray;

double msBetween(Clock::time_point inFrom, Clock::time_point inTo) {
  return std::chrono::duration<double, std::milli>(inTo - inFrom).count();
}

const char* const kUsage =
    "usage: sap_ros_latency [options] [ROS remappings]\n"
    "  --n N[,N...]            box counts (accepts 2^K; default 2^17,2^20)\n"
    "  --density D[,D...]      uniform-scene densities (default 0.05,0.35)\n"
    "  --frames F              measured frames per mode (default 20)\n"
    "  --warmup W              warm-up frames per mode, excluded (default 3)\n"
    "  --no-throughput         latency mode only\n"
    "  --transport T[,T...]    tcp (a node in another process), nodelet (the node loaded\n"
    "                          into this process); default tcp,nodelet\n"
    "  --seed S                scene seed (default 1)\n"
    "  --timeout S             seconds to wait for one frame's answer (default 120)\n"
    "  --out DIR               write ros_latency.csv and ros_latency_frames.csv into DIR\n"
    "  --quick                 n = 2^12,2^14, d = 0.05, 2 warm-up + 5 frames\n"
    "Topics (relative, remappable): boxes (published), pairs and stats (subscribed); for the\n"
    "nodelet transport the same names inside the namespace in_process.\n";

bool parseCount(const std::string& inText, std::size_t& outValue) {
  char* end = nullptr;
  if (inText.rfind("2^", 0) == 0) {
    const long exponent = std::strtol(inText.c_str() + 2, &end, 10);
    if (*end != '\0' || exponent < 1 || exponent > 26) return false;
    outValue = std::size_t{1} << exponent;
    return true;
  }
  const double value = std::strtod(inText.c_str(), &end);
  if (inText.empty() || *end != '\0' || !(value >= 2.0) || value > 67108864.0) return false;
  outValue = static_cast<std::size_t>(value);
  return true;
}

std::vector<std::string> splitComma(const std::string& inText) {
  std::vector<std::string> parts;
  std::stringstream stream(inText);
  std::string part;
  while (std::getline(stream, part, ','))
    if (!part.empty()) parts.push_back(part);
  return parts;
}

struct Options {
  std::vector<std::size_t> sizes{std::size_t{1} << 17, std::size_t{1} << 20};
  std::vector<double> densities{0.05, 0.35};
  int frames = 0;  // 0: by size
  int warmup = 3;
  bool throughput = true;
  std::vector<std::string> transports{"tcp", "nodelet"};
  uint64_t seed = 1;
  double timeout_s = 120.0;
  std::string out;
};

bool parseOptions(const std::vector<std::string>& inArgs, Options& outOptions) {
  for (std::size_t i = 0; i < inArgs.size(); ++i) {
    const std::string& arg = inArgs[i];
    auto next = [&](std::string& outValue) {
      if (i + 1 >= inArgs.size()) return false;
      outValue = inArgs[++i];
      return true;
    };
    std::string value;
    if (arg == "--quick") {
      outOptions.sizes = {std::size_t{1} << 12, std::size_t{1} << 14};
      outOptions.densities = {0.05};
      outOptions.warmup = 2;
      outOptions.frames = 5;
    } else if (arg == "--n" && next(value)) {
      outOptions.sizes.clear();
      for (const std::string& part : splitComma(value)) {
        std::size_t n = 0;
        if (!parseCount(part, n)) return false;
        outOptions.sizes.push_back(n);
      }
    } else if (arg == "--density" && next(value)) {
      outOptions.densities.clear();
      for (const std::string& part : splitComma(value)) {
        char* end = nullptr;
        const double d = std::strtod(part.c_str(), &end);
        if (*end != '\0' || !(d > 0.0) || d > 1.0) return false;
        outOptions.densities.push_back(d);
      }
    } else if (arg == "--frames" && next(value)) {
      outOptions.frames = std::atoi(value.c_str());
      if (outOptions.frames < 1) return false;
    } else if (arg == "--warmup" && next(value)) {
      outOptions.warmup = std::atoi(value.c_str());
      if (outOptions.warmup < 0) return false;
    } else if (arg == "--no-throughput") {
      outOptions.throughput = false;
    } else if (arg == "--transport" && next(value)) {
      outOptions.transports = splitComma(value);
      for (const std::string& transport : outOptions.transports)
        if (transport != "tcp" && transport != "nodelet") return false;
    } else if (arg == "--seed" && next(value)) {
      outOptions.seed = std::strtoull(value.c_str(), nullptr, 10);
    } else if (arg == "--timeout" && next(value)) {
      outOptions.timeout_s = std::atof(value.c_str());
      if (!(outOptions.timeout_s > 0.0)) return false;
    } else if (arg == "--out" && next(value)) {
      outOptions.out = value;
    } else {
      return false;
    }
  }
  return !outOptions.sizes.empty() && !outOptions.densities.empty() &&
         !outOptions.transports.empty();
}

/// What arrived for one stamp.
struct Reply {
  bool have_pairs = false;
  bool have_stats = false;
  Clock::time_point pairs_at;
  std::size_t pair_count = 0;
  std::size_t pair_bytes = 0;
  FrameStats stats;
};

/// Collects pairs and stats by stamp (callbacks run on one AsyncSpinner thread).
class Collector {
 public:
  void onPairs(const sap_broadphase::PairArrayConstPtr& inMsg) {
    const Clock::time_point now = Clock::now();
    std::lock_guard<std::mutex> lock(mutex_);
    Reply& reply = replies_[inMsg->header.stamp.toNSec()];
    reply.have_pairs = true;
    reply.pairs_at = now;
    reply.pair_count = inMsg->pairs.size() / 2;
    reply.pair_bytes = ros::serialization::serializationLength(*inMsg);
    last_pairs_ = inMsg;
    latest_pairs_stamp_ = std::max(latest_pairs_stamp_, inMsg->header.stamp.toNSec());
    changed_.notify_all();
  }
  void onStats(const sap_broadphase::FrameStatsConstPtr& inMsg) {
    std::lock_guard<std::mutex> lock(mutex_);
    Reply& reply = replies_[inMsg->header.stamp.toNSec()];
    reply.have_stats = true;
    reply.stats = *inMsg;
    changed_.notify_all();
  }
  /// Waits until the pairs and stats of inStamp arrived (pairs alone on timeout). Returns false
  /// on timeout or when a later frame's pairs came first (this one was dropped by the node).
  bool wait(uint64_t inStamp, double inTimeoutS, Reply& outReply) {
    std::unique_lock<std::mutex> lock(mutex_);
    const Clock::time_point deadline =
        Clock::now() +
        std::chrono::duration_cast<Clock::duration>(std::chrono::duration<double>(inTimeoutS));
    for (;;) {
      auto found = replies_.find(inStamp);
      if (found != replies_.end() && found->second.have_pairs && found->second.have_stats) {
        outReply = found->second;
        replies_.erase(found);
        return true;
      }
      const bool pairs_here = found != replies_.end() && found->second.have_pairs;
      // A later frame's pairs and none for this one: the node dropped it (one worker answers
      // frames in order, and `pairs` is one ordered connection).
      if (!pairs_here && latest_pairs_stamp_ > inStamp) return false;
      if (changed_.wait_until(lock, deadline) == std::cv_status::timeout) {
        found = replies_.find(inStamp);
        if (found != replies_.end() && found->second.have_pairs) {
          outReply = found->second;  // pairs without stats: keep the latency, stats stay zero
          replies_.erase(found);
          return true;
        }
        return false;
      }
    }
  }
  sap_broadphase::PairArrayConstPtr lastPairs() {
    std::lock_guard<std::mutex> lock(mutex_);
    return last_pairs_;
  }
  void clear() {
    std::lock_guard<std::mutex> lock(mutex_);
    replies_.clear();
  }

 private:
  std::mutex mutex_;
  std::condition_variable changed_;
  std::map<uint64_t, Reply> replies_;
  sap_broadphase::PairArrayConstPtr last_pairs_;
  uint64_t latest_pairs_stamp_ = 0;
};

/// One measured frame.
struct FrameRow {
  std::string transport;
  std::string mode;
  std::size_t n = 0;
  double density = 0.0;
  int frame = 0;
  uint64_t stamp = 0;
  std::size_t pairs = 0;
  std::size_t box_bytes = 0;
  std::size_t pair_bytes = 0;
  double publish_ms = 0.0;  // publish() call: tcp, serialisation + handing bytes to the socket
  double latency_ms = 0.0;  // publish() called -> pairs callback entered
  FrameStats stats;
  double sweep_ms() const { return stats.ms_sort + stats.ms_candidates + stats.ms_pairing; }
  double other_ms() const {
    return stats.ms_total - stats.ms_conversion - sweep_ms() - stats.ms_output;
  }
};

double median(std::vector<double> inValues) {
  if (inValues.empty()) return std::nan("");
  std::sort(inValues.begin(), inValues.end());
  const std::size_t mid = inValues.size() / 2;
  return inValues.size() % 2 ? inValues[mid] : 0.5 * (inValues[mid - 1] + inValues[mid]);
}

template <typename F>
double medianOf(const std::vector<FrameRow>& inRows, F inField) {
  std::vector<double> values;
  for (const FrameRow& row : inRows) values.push_back(inField(row));
  return median(values);
}

/// Offline cost of (de)serialising a message in this process, median of inRepeats.
template <typename M>
void serialisationCost(const M& inMsg, int inRepeats, double& outSerialiseMs,
                       double& outDeserialiseMs) {
  std::vector<double> ser, deser;
  for (int r = 0; r < inRepeats; ++r) {
    Clock::time_point start = Clock::now();
    ros::SerializedMessage bytes = ros::serialization::serializeMessage(inMsg);
    ser.push_back(msBetween(start, Clock::now()));
    M copy;
    start = Clock::now();
    ros::serialization::IStream stream(bytes.message_start,
                                       static_cast<uint32_t>(bytes.num_bytes - 4));
    ros::serialization::deserialize(stream, copy);
    deser.push_back(msBetween(start, Clock::now()));
  }
  outSerialiseMs = median(ser);
  outDeserialiseMs = median(deser);
}

struct Summary {
  std::string transport;
  std::string mode;
  std::size_t n = 0;
  double density = 0.0;
  int frames = 0;
  int lost = 0;
  double pairs = 0, box_mb = 0, pair_mb = 0;
  double latency = 0, publish = 0, node_total = 0, conversion = 0, sweep = 0, sort = 0,
         candidates = 0, pairing = 0, output = 0, other = 0, outside_node = 0, outside_sweep = 0,
         outside_share = 0, sweep_share = 0, fps = 0;
  double ser_boxes = 0, deser_boxes = 0, ser_pairs = 0, deser_pairs = 0;
  uint64_t dropped = 0;
  std::string path;
  int threads = 0;
};

Summary summarise(const std::string& inTransport, const std::string& inMode, std::size_t inN,
                  double inDensity, const std::vector<FrameRow>& inRows, int inLost) {
  Summary s;
  s.transport = inTransport;
  s.mode = inMode;
  s.n = inN;
  s.density = inDensity;
  s.frames = static_cast<int>(inRows.size());
  s.lost = inLost;
  if (inRows.empty()) return s;
  s.pairs = medianOf(inRows, [](const FrameRow& r) { return double(r.pairs); });
  s.box_mb = medianOf(inRows, [](const FrameRow& r) { return r.box_bytes / 1e6; });
  s.pair_mb = medianOf(inRows, [](const FrameRow& r) { return r.pair_bytes / 1e6; });
  s.latency = medianOf(inRows, [](const FrameRow& r) { return r.latency_ms; });
  s.publish = medianOf(inRows, [](const FrameRow& r) { return r.publish_ms; });
  s.node_total = medianOf(inRows, [](const FrameRow& r) { return r.stats.ms_total; });
  s.conversion = medianOf(inRows, [](const FrameRow& r) { return r.stats.ms_conversion; });
  s.sweep = medianOf(inRows, [](const FrameRow& r) { return r.sweep_ms(); });
  s.sort = medianOf(inRows, [](const FrameRow& r) { return r.stats.ms_sort; });
  s.candidates = medianOf(inRows, [](const FrameRow& r) { return r.stats.ms_candidates; });
  s.pairing = medianOf(inRows, [](const FrameRow& r) { return r.stats.ms_pairing; });
  s.output = medianOf(inRows, [](const FrameRow& r) { return r.stats.ms_output; });
  s.other = medianOf(inRows, [](const FrameRow& r) { return r.other_ms(); });
  s.outside_node =
      medianOf(inRows, [](const FrameRow& r) { return r.latency_ms - r.stats.ms_total; });
  s.outside_sweep = medianOf(inRows, [](const FrameRow& r) { return r.latency_ms - r.sweep_ms(); });
  s.outside_share = medianOf(
      inRows, [](const FrameRow& r) { return (r.latency_ms - r.sweep_ms()) / r.latency_ms; });
  s.sweep_share = 1.0 - s.outside_share;
  s.dropped = inRows.back().stats.frames_dropped - inRows.front().stats.frames_dropped;
  s.path = inRows.back().stats.path;
  s.threads = static_cast<int>(inRows.back().stats.threads);
  return s;
}

/// The next inCount frames of the simulator as messages (the motion goes on across calls).
void makeFrames(sap_broadphase::SceneSimulator& ioSimulator, int inCount,
                std::vector<BoxArrayPtr>& outFrames) {
  outFrames.clear();
  for (int i = 0; i < inCount; ++i) {
    BoxArrayPtr msg = boost::make_shared<BoxArray>();
    msg->header.frame_id = "map";
    sap_broadphase::boxSetToBoxArray(ioSimulator.boxes(), msg->header, *msg);
    msg->ids.clear();  // as scene_publisher: boxes numbered 0..n-1
    outFrames.push_back(msg);
    ioSimulator.step();
  }
}

/// One transport's publisher and subscribers, in the namespace of ioNode.
class Runner {
 public:
  Runner(ros::NodeHandle& ioNode, const std::string& inTransport, const Options& inOptions)
      : options_(inOptions), transport_(inTransport) {
    boxes_pub_ = ioNode.advertise<BoxArray>("boxes", 4);
    pairs_sub_ = ioNode.subscribe("pairs", 10, &Collector::onPairs, &collector_,
                                  ros::TransportHints().tcpNoDelay());
    stats_sub_ = ioNode.subscribe("stats", 50, &Collector::onStats, &collector_,
                                  ros::TransportHints().tcpNoDelay());
  }

  bool waitForConnections(double inTimeoutS) {
    const Clock::time_point deadline =
        Clock::now() + std::chrono::milliseconds(static_cast<int>(inTimeoutS * 1000));
    while (ros::ok() && Clock::now() < deadline) {
      if (boxes_pub_.getNumSubscribers() > 0 && pairs_sub_.getNumPublishers() > 0 &&
          stats_sub_.getNumPublishers() > 0) {
        ros::Duration(0.3).sleep();  // let the other ends finish their handshakes
        return true;
      }
      ros::Duration(0.05).sleep();
    }
    return false;
  }

  /// Publishes frames [inFirst, inFirst + inCount) with inInFlight frames in flight; appends the
  /// frames from inFirst + inWarmup on to outRows. Returns the frames lost (no answer).
  int run(const std::string& inMode, std::size_t inN, double inDensity,
          std::vector<BoxArrayPtr>& ioFrames, int inFirst, int inWarmup, int inCount,
          int inInFlight, std::vector<FrameRow>& outRows, double& outFps) {
    struct Sent {
      uint64_t stamp;
      Clock::time_point at;
      double publish_ms;
      int index;
    };
    std::vector<Sent> sent;
    int lost = 0;
    int next = 0;
    auto publishNext = [&]() {
      BoxArrayPtr& msg = ioFrames[static_cast<std::size_t>(inFirst + next)];
      // The frames are published again by the next transport: a message someone still holds
      // (a node that dropped it, a queue) is copied, never written while shared.
      if (msg.use_count() > 1) msg = boost::make_shared<BoxArray>(*msg);
      ros::Time stamp = ros::Time::now();
      if (stamp.toNSec() <= last_stamp_) stamp.fromNSec(last_stamp_ + 1);
      last_stamp_ = stamp.toNSec();
      msg->header.stamp = stamp;
      const Clock::time_point start = Clock::now();
      // A shared pointer: serialised here, before returning, for a subscriber in another
      // process; handed over as it is to one in this process.
      boxes_pub_.publish(msg);
      const Clock::time_point end = Clock::now();
      sent.push_back({stamp.toNSec(), start, msBetween(start, end), next});
      ++next;
    };
    while (next < inCount && next < inInFlight) publishNext();
    Clock::time_point first_measured_reply{}, last_reply{};
    int measured_replies = 0;
    for (std::size_t waited = 0; waited < sent.size() && ros::ok(); ++waited) {
      const Sent& frame = sent[waited];
      Reply reply;
      const bool ok = collector_.wait(frame.stamp, options_.timeout_s, reply);
      if (next < inCount) publishNext();
      if (!ok) {
        std::cerr << "sap_ros_latency: no answer for frame " << frame.index << " (" << inMode
                  << ", n " << inN << ", d " << inDensity << ")\n";
        if (frame.index >= inWarmup) ++lost;
        continue;
      }
      if (frame.index < inWarmup) continue;
      if (measured_replies == 0) first_measured_reply = reply.pairs_at;
      last_reply = reply.pairs_at;
      ++measured_replies;
      FrameRow row;
      row.transport = transport_;
      row.mode = inMode;
      row.n = inN;
      row.density = inDensity;
      row.frame = frame.index;
      row.stamp = frame.stamp;
      row.pairs = reply.pair_count;
      row.box_bytes = ros::serialization::serializationLength(
          *ioFrames[static_cast<std::size_t>(inFirst + frame.index)]);
      row.pair_bytes = reply.pair_bytes;
      row.publish_ms = frame.publish_ms;
      row.latency_ms = msBetween(frame.at, reply.pairs_at);
      row.stats = reply.stats;
      if (reply.stats.pairs != reply.pair_count)
        std::cerr << "sap_ros_latency: stats say " << reply.stats.pairs << " pairs, pairs has "
                  << reply.pair_count << "\n";
      outRows.push_back(row);
    }
    outFps = measured_replies > 1
                 ? (measured_replies - 1) / (msBetween(first_measured_reply, last_reply) / 1e3)
                 : std::nan("");
    collector_.clear();
    return lost;
  }

  Collector& collector() { return collector_; }
  const std::string& transport() const { return transport_; }

 private:
  const Options& options_;
  std::string transport_;
  ros::Publisher boxes_pub_;
  ros::Subscriber pairs_sub_;
  ros::Subscriber stats_sub_;
  Collector collector_;
  uint64_t last_stamp_ = 0;
};

void printTable(const std::vector<Summary>& inSummaries) {
  std::printf(
      "\n%-7s %-10s %8s %5s %3s %4s %8s %7s %6s | %8s %7s %8s %7s %7s %7s %6s | %8s %8s %6s "
      "%6s\n",
      "trans", "mode", "n", "d", "fr", "lost", "pairs", "box MB", "prs MB", "latency", "publish",
      "out-node", "conv", "sweep", "output", "other", "node tot", "out-swp", "share", "fps");
  for (const Summary& s : inSummaries) {
    std::printf(
        "%-7s %-10s %8zu %5.2f %3d %4d %8.0f %7.1f %6.2f | %8.2f %7.2f %8.2f %7.2f %7.2f %7.2f "
        "%6.2f | %8.2f %8.2f %5.1f%% %6.2f\n",
        s.transport.c_str(), s.mode.c_str(), s.n, s.density, s.frames, s.lost, s.pairs, s.box_mb,
        s.pair_mb, s.latency, s.publish, s.outside_node, s.conversion, s.sweep, s.output, s.other,
        s.node_total, s.outside_sweep, 100.0 * s.outside_share, s.fps);
  }
  std::printf(
      "(ms, medians over frames. trans: tcp = node in another process, nodelet = node loaded\n"
      " into this process. latency: publish() called -> pairs callback entered. out-node:\n"
      " latency - node ms_total (publisher serialisation, transport, node deserialisation and\n"
      " hand-off, pairs transport and deserialisation; with the nodelet only the hand-offs and\n"
      " whatever the node still serialises). conv: BoxArray -> BoxSet + validation.\n"
      " sweep: ms_sort + ms_candidates + ms_pairing. output: engine canonical pair order +\n"
      " PairArray fill + publish(). other: rest of ms_total (engine bookkeeping, frame copy for\n"
      " reuse). out-swp: latency - sweep; share: its fraction of latency. fps: answers per second\n"
      " in throughput mode, 2 frames in flight.)\n");
  for (const Summary& s : inSummaries) {
    if (s.mode != "latency" || s.transport != "tcp") continue;
    std::printf(
        "offline in this process, n %zu d %.2f: BoxArray serialise %.2f ms, deserialise %.2f ms;"
        " PairArray serialise %.2f ms, deserialise %.2f ms\n",
        s.n, s.density, s.ser_boxes, s.deser_boxes, s.ser_pairs, s.deser_pairs);
  }
}

bool writeCsv(const std::string& inDir, const std::vector<Summary>& inSummaries,
              const std::vector<FrameRow>& inRows) {
  std::ofstream summary(inDir + "/ros_latency.csv");
  summary << "transport,mode,n,density,frames,lost,threads,path,pairs,box_msg_mb,pair_msg_mb,"
             "latency_ms,"
             "publish_ms,outside_node_ms,conversion_ms,sort_ms,candidates_ms,pairing_ms,"
             "sweep_ms,output_ms,other_ms,node_total_ms,outside_sweep_ms,outside_sweep_share,"
             "throughput_fps,node_dropped,offline_serialise_boxes_ms,"
             "offline_deserialise_boxes_ms,offline_serialise_pairs_ms,"
             "offline_deserialise_pairs_ms\n";
  for (const Summary& s : inSummaries) {
    summary << s.transport << ',' << s.mode << ',' << s.n << ',' << s.density << ',' << s.frames
            << ',' << s.lost << ',' << s.threads << ',' << s.path << ',' << s.pairs << ','
            << s.box_mb << ',' << s.pair_mb << ',' << s.latency << ',' << s.publish << ','
            << s.outside_node << ',' << s.conversion << ',' << s.sort << ',' << s.candidates << ','
            << s.pairing << ',' << s.sweep << ',' << s.output << ',' << s.other << ','
            << s.node_total << ',' << s.outside_sweep << ',' << s.outside_share << ',' << s.fps
            << ',' << s.dropped << ',' << s.ser_boxes << ',' << s.deser_boxes << ',' << s.ser_pairs
            << ',' << s.deser_pairs << '\n';
  }
  std::ofstream frames(inDir + "/ros_latency_frames.csv");
  frames << "transport,mode,n,density,frame,stamp_ns,pairs,box_msg_bytes,pair_msg_bytes,publish_ms,"
            "latency_ms,conversion_ms,sort_ms,candidates_ms,pairing_ms,output_ms,node_total_ms,"
            "path,threads,frames_dropped\n";
  for (const FrameRow& r : inRows) {
    frames << r.transport << ',' << r.mode << ',' << r.n << ',' << r.density << ',' << r.frame
           << ',' << r.stamp << ',' << r.pairs << ',' << r.box_bytes << ',' << r.pair_bytes << ','
           << r.publish_ms << ',' << r.latency_ms << ',' << r.stats.ms_conversion << ','
           << r.stats.ms_sort << ',' << r.stats.ms_candidates << ',' << r.stats.ms_pairing << ','
           << r.stats.ms_output << ',' << r.stats.ms_total << ',' << r.stats.path << ','
           << r.stats.threads << ',' << r.stats.frames_dropped << '\n';
  }
  return summary.good() && frames.good();
}

/// Namespace of the nodelet transport's topics and of the nodelet loaded into this process.
const char* const kInProcessNamespace = "in_process";

/// Loads sap_broadphase/BroadphaseNodelet into this process as in_process/sap_broadphase, with
/// the settings bench_ros.sh gives the node of the tcp transport (no markers, the rest default).
bool loadBroadphaseNodelet(nodelet::Loader& ioLoader) {
  const std::string name =
      ros::names::resolve(std::string(kInProcessNamespace) + "/sap_broadphase");
  ros::param::set(name + "/publish_markers", false);
  return ioLoader.load(name, "sap_broadphase/BroadphaseNodelet", ros::M_string(),
                       std::vector<std::string>());
}

}  // namespace

int main(int argc, char** argv) {
  ros::init(argc, argv, "sap_ros_latency", ros::init_options::AnonymousName);
  std::vector<std::string> args;
  ros::removeROSArgs(argc, argv, args);
  args.erase(args.begin());
  Options options;
  if (!parseOptions(args, options)) {
    std::cerr << kUsage;
    return 2;
  }
  ros::AsyncSpinner spinner(1);
  spinner.start();
  // The loader outlives the runners (declared first): their subscribers go before its node.
  std::optional<nodelet::Loader> loader;
  std::vector<std::unique_ptr<Runner>> runners;
  for (const std::string& transport : options.transports) {
    const bool in_process = transport == "nodelet";
    if (in_process) {
      loader.emplace(false);  // no load/unload services: only this process loads nodelets
      if (!loadBroadphaseNodelet(*loader)) {
        std::cerr << "sap_ros_latency: could not load sap_broadphase/BroadphaseNodelet (is the "
                     "workspace's setup.bash sourced?)\n";
        return 1;
      }
    }
    ros::NodeHandle node(in_process ? kInProcessNamespace : "");
    runners.push_back(std::make_unique<Runner>(node, transport, options));
    if (!runners.back()->waitForConnections(30.0)) {
      std::cerr << "sap_ros_latency: no node on " << node.resolveName("boxes")
                << "/pairs/stats after 30 s\n";
      return 1;
    }
  }

  std::vector<Summary> summaries;
  std::vector<FrameRow> all_rows;
  int total_lost = 0;
  for (std::size_t n : options.sizes) {
    for (double density : options.densities) {
      const int frames = options.frames > 0 ? options.frames : 20;
      const int per_mode = options.warmup + frames;
      std::cerr << "sap_ros_latency: n " << n << ", d " << density << ": " << options.warmup
                << " warm-up + " << frames << " frames per mode and transport\n";
      sap_broadphase::SceneConfig scene;
      scene.kind = sap_broadphase::SceneKind::kUniform;
      scene.n = n;
      scene.density = density;
      scene.seed = options.seed;
      sap_broadphase::SceneSimulator simulator(scene);
      std::vector<BoxArrayPtr> messages;
      makeFrames(simulator, per_mode, messages);

      // Every transport gets the same frames, one after the other, so that a load change on
      // the machine shows as a difference between neighbouring rows, not between runs.
      for (auto& runner : runners) {
        std::vector<FrameRow> rows;
        double fps = 0.0;
        const int lost =
            runner->run("latency", n, density, messages, 0, options.warmup, per_mode, 1, rows, fps);
        total_lost += lost;
        Summary latency = summarise(runner->transport(), "latency", n, density, rows, lost);
        latency.fps = fps;  // one in flight: 1 / (latency + this process's gaps)
        serialisationCost(*messages[0], 3, latency.ser_boxes, latency.deser_boxes);
        if (auto pairs = runner->collector().lastPairs())
          serialisationCost(*pairs, 3, latency.ser_pairs, latency.deser_pairs);
        summaries.push_back(latency);
        all_rows.insert(all_rows.end(), rows.begin(), rows.end());
        std::cerr << "sap_ros_latency:   " << runner->transport() << " latency mode: median "
                  << latency.latency << " ms, sweep " << latency.sweep << " ms\n";
      }

      if (options.throughput) {
        // The throughput frames continue the motion of the latency frames.
        // Two in flight can lose a frame by design ("latest frame wins" when the worker is
        // slow to pick up the pending one): counted in `lost`, not an error.
        makeFrames(simulator, per_mode, messages);
        for (auto& runner : runners) {
          std::vector<FrameRow> rows;
          double fps = 0.0;
          const int lost = runner->run("throughput", n, density, messages, 0, options.warmup,
                                       per_mode, 2, rows, fps);
          Summary throughput = summarise(runner->transport(), "throughput", n, density, rows, lost);
          throughput.fps = fps;
          summaries.push_back(throughput);
          all_rows.insert(all_rows.end(), rows.begin(), rows.end());
          std::cerr << "sap_ros_latency:   " << runner->transport() << " throughput mode: " << fps
                    << " frames/s\n";
        }
      }
    }
  }
  printTable(summaries);
  std::fflush(stdout);
  if (!options.out.empty() && !writeCsv(options.out, summaries, all_rows)) {
    std::cerr << "sap_ros_latency: could not write CSV into " << options.out << "\n";
    return 1;
  }
  runners.clear();
  spinner.stop();
  if (total_lost > 0) {
    std::cerr << "sap_ros_latency: " << total_lost << " latency-mode frames got no answer\n";
    return 3;
  }
  return 0;
}
