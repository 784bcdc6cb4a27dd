// The scan sources of tacs_offline (a bag, or a world simulated in-process) and the thread that
// reads it and runs the odometry a few scans ahead of the keyframe stages (OdometryAhead).
#pragma once

#include <pcl/common/transforms.h>

#include <atomic>
#include <exception>
#include <functional>
#include <future>
#include <iostream>
#include <optional>
#include <string>
#include <thread>
#include <utility>

#include "tacs_graphs/common/bounded_queue.h"
#include "tacs_graphs/common/trajectory_io.h"
#include "tacs_graphs/pipeline/pipeline.h"
#include "tacs_graphs/ros/bag_scan_source.h"
#include "tacs_graphs/sim/ground_truth.h"
#include "tacs_graphs/sim/scan_stream.h"

namespace tacs::tools {

/// One scan in the sensor frame, from a bag or the simulator.
struct SensorScan {
  double stamp = 0.0;
  std::string frame_id;
  tacs::PointCloud cloud;
  std::string error;       // the message could not be used
  tacs::PointTimes times;  // per-point times relative to `stamp` (times.ok: usable)
};

/// next() and baseToSensor() run on OdometryAhead's reading thread; size() (fixed at opening) and
/// the ground truth are read by the caller.
class ScanSource {
 public:
  virtual ~ScanSource() = default;
  virtual bool next(SensorScan* scan) = 0;
  virtual size_t size() const = 0;
  /// T_base_sensor for the frame of the first scan.
  virtual tacs::Pose3 baseToSensor(const std::string& frame_id) = 0;
  /// Ground-truth trajectory of the base, empty when the source has none.
  virtual tacs::Trajectory groundTruth() const = 0;
  virtual void writeGroundTruth(const std::string& dir) = 0;
};

class BagSource : public ScanSource {
 public:
  BagSource(const std::string& bag, const std::string& topic, const tacs::FramesConfig& frames,
            const tacs::PointTimeConfig& point_times)
      : bag_(bag, topic, point_times), frames_(frames) {}
  bool next(SensorScan* scan) override {
    tacs::BagScanSource::Scan s;
    if (!bag_.next(&s)) return false;
    scan->stamp = s.stamp;
    scan->frame_id = s.frame_id;
    scan->cloud = std::move(s.cloud);
    scan->error = s.conversion.ok ? "" : s.conversion.error;
    scan->times = std::move(s.times);
    return true;
  }
  size_t size() const override { return bag_.messageCount(); }
  tacs::Pose3 baseToSensor(const std::string& frame_id) override {
    const std::string sensor = frames_.sensor_frame.empty() ? frame_id : frames_.sensor_frame;
    if (const auto T = bag_.lookupTransform(frames_.base_frame, sensor)) {
      std::cerr << "[tacs_offline] extrinsic " << frames_.base_frame << " -> " << sensor
                << " from the bag's TF\n";
      return *T;
    }
    std::cerr << "[tacs_offline] no TF " << frames_.base_frame << " -> " << sensor
              << " in the bag: using frames.base_to_sensor\n";
    return frames_.baseToSensor();
  }
  // Bags written by tacs_sim carry their ground truth; it is kept beside the run.
  tacs::Trajectory groundTruth() const override {
    return bag_.readOdometryTopic("/ground_truth/odom");
  }
  void writeGroundTruth(const std::string& dir) override {
    const tacs::Trajectory gt = groundTruth();
    if (!gt.empty()) tacs::writeTum(dir + "/ground_truth_tum.txt", gt);
  }

 private:
  tacs::BagScanSource bag_;
  tacs::FramesConfig frames_;
};

class WorldSource : public ScanSource {
 public:
  WorldSource(const std::string& world, const tacs::sim::SimOptions& sim,
              const tacs::PointTimeConfig& point_times)
      : world_(tacs::sim::loadWorld(world)), stream_(world_, sim), point_times_(point_times) {}
  bool next(SensorScan* scan) override {
    // The next sweep is cast while the pipeline handles this one (rendering is pure: the sweep
    // is the same whichever thread casts it).
    if (!ahead_.valid()) ahead_ = renderAhead();
    std::optional<tacs::sim::SimScan> rendered = ahead_.get();
    if (!rendered) return false;
    ahead_ = renderAhead();
    const tacs::sim::SimScan& s = *rendered;
    scan->stamp = s.stamp;
    scan->frame_id = "velodyne";
    scan->cloud = tacs::sim::toPointCloud(s);
    // The times go through the same detection as a bag's field, in the world's convention. A
    // world without motion distortion renders each sweep from one pose: nothing to deskew.
    const std::string field = stream_.sensor().time_field;
    if (stream_.sensor().motion_distortion && point_times_.time_field != "none") {
      scan->times =
          tacs::resolvePointTimes(field, tacs::sim::rawPointTimes(s, field), s.stamp, point_times_);
    }
    return true;
  }
  size_t size() const override { return stream_.scanCount(); }
  tacs::Pose3 baseToSensor(const std::string&) override { return stream_.baseToSensor(); }
  tacs::Trajectory groundTruth() const override { return stream_.groundTruth(); }
  void writeGroundTruth(const std::string& dir) override {
    tacs::writeTum(dir + "/ground_truth_tum.txt", stream_.groundTruth());
    tacs::sim::writeGroundTruth(dir + "/ground_truth.json", tacs::sim::groundTruthOf(world_));
  }

 private:
  std::future<std::optional<tacs::sim::SimScan>> renderAhead() {
    return std::async(std::launch::async, [this]() -> std::optional<tacs::sim::SimScan> {
      tacs::sim::SimScan s;
      if (!stream_.next(&s)) return std::nullopt;
      return s;
    });
  }

  tacs::sim::World world_;
  tacs::sim::ScanStream stream_;
  tacs::PointTimeConfig point_times_;
  std::future<std::optional<tacs::sim::SimScan>> ahead_;
};

/// One message of the source after the odometry thread: a scan's odometry, or why the message
/// was no usable scan.
struct ScanItem {
  size_t k = 0;       // 1-based position in the source
  std::string error;  // the message could not be used (nothing else is set)
  double stamp = 0.0;
  std::string no_deskew, no_deskew_message;  // the scan's times were unusable: reason, message
  tacs::ScanOdometry odometry;
};

/// Reads the source on a thread of its own (decompression, conversion, the move into the base
/// frame, the odometry's preparation: Pipeline::prepareScan), up to kReadDepth scans ahead, and
/// runs the odometry (Pipeline::odometryOf) on another, up to kDepth scans ahead of the caller,
/// who takes each scan's odometry on in order (Pipeline::takeOdometry): the keyframe stages of
/// one scan overlap the odometry of the next ones, whose reading overlaps both, and every result
/// is what the sequential loop gives. The pipeline is made by `make_pipeline(T_base_sensor)` on
/// the reading thread at the first usable scan, when the sensor's extrinsic is known.
class OdometryAhead {
 public:
  static constexpr size_t kDepth = 8;
  static constexpr size_t kReadDepth = 3;

  OdometryAhead(ScanSource& source,
                std::function<tacs::Pipeline*(const tacs::Pose3&)> make_pipeline)
      : source_(source),
        make_pipeline_(std::move(make_pipeline)),
        reader_([this] { read(); }),
        thread_([this] { run(); }) {}
  ~OdometryAhead() { stop(); }

  /// The next message's item, or nullopt at the end (or once a thread failed: finish()).
  std::optional<ScanItem> next() { return queue_.pop(); }

  /// Waits for the threads and rethrows what stopped them early, if anything did.
  void finish() {
    stop();
    if (failure_) std::rethrow_exception(failure_);
  }

 private:
  // A message as read: its item with all but the position and the odometry, and a usable scan
  // in the base frame prepared for the odometry (Pipeline::prepareScan).
  struct ReadScan {
    ScanItem item;
    tacs::Pipeline* pipeline = nullptr;  // made on the first usable scan
    tacs::PreparedScan prepared;
  };

  void stop() {
    queue_.close();
    read_queue_.close();
    if (thread_.joinable()) thread_.join();
    if (reader_.joinable()) reader_.join();
  }

  // The source is read on this thread only (next() and baseToSensor() alike); the pipeline is
  // made here, at the first usable scan, when the sensor's extrinsic is known.
  void read() {
    try {
      tacs::Pipeline* pipeline = nullptr;
      Eigen::Affine3f base_to_sensor = Eigen::Affine3f::Identity();
      SensorScan scan;
      while (source_.next(&scan)) {
        ReadScan read;
        ScanItem& item = read.item;
        item.error = scan.error;
        if (item.error.empty()) {
          if (!pipeline) {
            const tacs::Pose3 T_base_sensor = source_.baseToSensor(scan.frame_id);
            base_to_sensor = T_base_sensor.cast<float>();
            pipeline = make_pipeline_(T_base_sensor);
          }
          auto in_base = std::make_shared<tacs::PointCloud>();
          pcl::transformPointCloud(scan.cloud, *in_base, base_to_sensor);
          tacs::PointTimes& times = scan.times;
          if (!times.ok && !times.reason.empty() && times.reason != "disabled") {
            item.no_deskew = times.reason;
            item.no_deskew_message = times.message;
          }
          item.stamp = scan.stamp;
          read.pipeline = pipeline;
          read.prepared = pipeline->prepareScan(
              scan.stamp, std::move(in_base),
              times.ok ? std::make_shared<std::vector<float>>(std::move(times.offset_s)) : nullptr);
        }
        if (!read_queue_.push(std::move(read))) return;  // the odometry thread stopped
      }
    } catch (...) {
      read_failure_ = std::current_exception();
    }
    read_queue_.close();
  }

  void run() {
    try {
      for (size_t k = 1;; ++k) {
        std::optional<ReadScan> read = read_queue_.pop();
        if (!read) break;
        ScanItem& item = read->item;
        item.k = k;
        if (item.error.empty()) item.odometry = read->pipeline->odometryOf(read->prepared);
        if (!queue_.push(std::move(item))) break;  // the caller stopped taking scans
      }
      read_queue_.close();  // the reader may wait on a full queue
      if (reader_.joinable()) reader_.join();
      if (read_failure_) failure_ = read_failure_;
    } catch (...) {
      failure_ = std::current_exception();
    }
    queue_.close();
  }

  ScanSource& source_;
  std::function<tacs::Pipeline*(const tacs::Pose3&)> make_pipeline_;
  tacs::BoundedQueue<ReadScan> read_queue_{kReadDepth};
  tacs::BoundedQueue<ScanItem> queue_{kDepth};
  std::exception_ptr read_failure_, failure_;
  std::thread reader_;  // last: started once everything they use is built
  std::thread thread_;
};

}  // namespace tacs::tools
