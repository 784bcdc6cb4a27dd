#include "tacs_graphs/ros/backend_node.h"

#include <tacs_graphs/Resync.h>
#include <tacs_graphs/SceneGraph.h>
#include <visualization_msgs/MarkerArray.h>

#include <cmath>
#include <cstdlib>

#include "tacs_graphs/common/file_io.h"
#include "tacs_graphs/ros/cloud_conversion.h"
#include "tacs_graphs/ros/graph_messages.h"
#include "tacs_graphs/ros/keyframe_input.h"
#include "tacs_graphs/ros/message_conversion.h"
#include "tacs_graphs/ros/params.h"
#include "tacs_graphs/ros/resend_buffer.h"
#include "tacs_graphs/ros/scene_graph_markers.h"

namespace tacs {
namespace {

// Channels of the crash journal.
enum JournalChannel : uint8_t { kKeyframeChannel, kWallsChannel, kRoomsChannel, kLoopsChannel };

// A graph built from fewer scans than this share of the sensor's is saved with a warning.
constexpr double kUnreliableDropRatio = 0.05;

// With a prior map, the save's subfolder holding the session in the prior's frame.
constexpr char kPriorFrameFolder[] = "in_prior";

std::string defaultOutputDir() {
  if (const char* ros_home = std::getenv("ROS_HOME")) return std::string(ros_home) + "/tacs_graphs";
  const char* home = std::getenv("HOME");
  return std::string(home ? home : "/tmp") + "/.ros/tacs_graphs";
}

/// Distance along the keyframes in id (= arrival) order.
double drivenDistance(const SceneGraph& graph) {
  double d = 0.0;
  const KeyframeNode* last = nullptr;
  for (const auto& [id, kf] : graph.keyframes) {
    if (last) d += (kf.position - last->position).norm();
    last = &kf;
  }
  return d;
}

}  // namespace

BackendNode::BackendNode(ros::NodeHandle& nh, ros::NodeHandle& pnh) : pnh_(pnh) {
  const std::string config_ns = pnh.param<std::string>("config_ns", "/tacs");
  config_ = loadPipelineConfigFromRos(nh, config_ns);
  output_dir_ = pnh.param<std::string>("output_dir", "");
  if (output_dir_.empty()) output_dir_ = defaultOutputDir();
  save_on_shutdown_ = pnh.param("save_on_shutdown", true);
  session_ = std::make_unique<BackendSession>(config_, BackendSessionOptions());
  if (pnh.param("recover", false)) {
    try {
      const size_t n = session_->recover(output_dir_);
      ROS_INFO_STREAM("Recovered " << n << " keyframes from " << output_dir_);
    } catch (const std::exception& e) {
      ROS_WARN_STREAM("Nothing recovered: " << e.what());
    }
  }

  journal_ = std::make_unique<NodeJournal>(pnh, "backend");
  if (journal_->mustReplay()) replayJournal();

  graph_pub_ = nh.advertise<tacs_graphs::SceneGraph>("/tacs/scene_graph", 1, /*latch=*/true);
  marker_pub_ = nh.advertise<visualization_msgs::MarkerArray>("/tacs/markers", 1, /*latch=*/true);
  map_pub_ = nh.advertise<sensor_msgs::PointCloud2>("/tacs/map_points", 1, /*latch=*/true);
  const ros::TransportHints hints = ros::TransportHints().tcpNoDelay();
  keyframe_sub_ = nh.subscribe("/tacs/keyframe", 1000, &BackendNode::keyframeCallback, this, hints);
  walls_sub_ =
      nh.subscribe("/tacs/wall_observations", 1000, &BackendNode::wallsCallback, this, hints);
  rooms_sub_ =
      nh.subscribe("/tacs/room_observations", 100, &BackendNode::roomsCallback, this, hints);
  loop_sub_ = nh.subscribe("/tacs/loop_closures", 100, &BackendNode::loopCallback, this, hints);
  save_srv_ = pnh.advertiseService("save", &BackendNode::saveService, this);
  prior_marker_pub_ =
      nh.advertise<visualization_msgs::MarkerArray>("/tacs/prior_markers", 1, /*latch=*/true);
  load_prior_srv_ = pnh.advertiseService("load_prior", &BackendNode::loadPriorService, this);
  if (!pnh.param<std::string>("prior_map", "").empty()) {
    std::string message;
    loadPrior(&message);  // a bad prior is logged; the node maps on without one
  }
  tf_timer_ = nh.createTimer(ros::Duration(1.0 / boundedParam(pnh, "tf_rate_hz", 20.0, 0.0, false)),
                             &BackendNode::publishTf, this);
  map_timer_ =
      nh.createTimer(ros::Duration(boundedParam(pnh, "map_publish_period_s", 5.0, 0.0, false)),
                     &BackendNode::publishMap, this);
  if (session_->keyframeCount() > 0) update();
  if (journal_->mustReplay()) {
    resync_from_ = session_->firstIncompleteKeyframe();
    resync_pub_ = requestResync(nh, "backend", *resync_from_);
  }
  ROS_INFO_STREAM("Backend ready; products go to " << output_dir_);
}

void BackendNode::replayJournal() {
  journal_->replay([this](uint8_t channel, const std::vector<uint8_t>& bytes) {
    switch (channel) {
      case kKeyframeChannel:
        keyframeCallback(MessageJournal::deserialize<tacs_graphs::Keyframe>(bytes));
        break;
      case kWallsChannel:
        wallsCallback(MessageJournal::deserialize<tacs_graphs::WallObservations>(bytes));
        break;
      case kRoomsChannel:
        roomsCallback(MessageJournal::deserialize<tacs_graphs::RoomObservations>(bytes));
        break;
      case kLoopsChannel:
        loopCallback(MessageJournal::deserialize<tacs_graphs::LoopClosure>(bytes));
        break;
      default:
        warnings_.warn("journal", "record of an unknown channel skipped");
    }
  });
  if (session_->keyframeCount() > 0) session_->optimize();
  const std::vector<uint32_t> missing = session_->missingKeyframes();
  ROS_WARN_STREAM("backend: recovered " << session_->keyframeCount() << " keyframes (newest "
                                        << session_->newestKeyframe() << "), "
                                        << session_->roomCount() << " rooms; " << missing.size()
                                        << " keyframe id(s) never received");
}

void BackendNode::keyframeCallback(const tacs_graphs::Keyframe::ConstPtr& msg) {
  const KeyframeInput kf = fromKeyframeMsg(*msg);
  if (!kf.ok) {
    warnings_.warn("keyframe", WarnOnce::reasonKey(kf.error), kf.error + ", skipped");
    return;
  }
  // The odometry numbers its keyframes one by one: a jump is keyframes lost on the way.
  // After a restart the keyframes of the downtime come later, resent (the Resync).
  const bool resend_due = resync_from_ && kf.id > *resync_from_;
  if (session_->keyframeCount() > 0 && kf.id > session_->newestKeyframe() + 1 && !resend_due) {
    ROS_WARN_STREAM("keyframe: " << kf.id - session_->newestKeyframe() - 1
                                 << " keyframe(s) before id " << kf.id
                                 << " never arrived (a full queue on /tacs/keyframe or an "
                                    "odometry restart); the graph has a gap there");
  }
  const auto outcome =
      session_->addKeyframe(kf.id, kf.stamp, kf.T_odom_base, kf.information, kf.cloud);
  if (outcome == BackendSession::Outcome::kDuplicate) {
    warnings_.warn("keyframe", "keyframe id already in the graph (resent), skipped");
    return;
  }
  journal_->record(kKeyframeChannel, *msg);
  session_->noteScanInput({msg->scans_received, msg->scans_missing});
  session_->noteSensorInBase(kf.sensor_in_base);
  latest_stamp_ = std::max(latest_stamp_, kf.stamp);
  map_dirty_ = true;
  changed_ = true;
}

void BackendNode::wallsCallback(const tacs_graphs::WallObservations::ConstPtr& msg) {
  const auto valid = [this](const std::vector<tacs_graphs::WallObservation>& observations) {
    std::vector<WallSegment> segments;
    segments.reserve(observations.size());
    for (const auto& w : observations) {
      const WallSegment s = fromWallObservationMsg(w);
      if (!s.normal.allFinite() || !std::isfinite(s.d) || s.normal.norm() < 0.5) {
        warnings_.warn("wall observations", "non-finite or zero plane, observation skipped");
        continue;
      }
      segments.push_back(s);
    }
    return segments;
  };
  KeyframeWalls walls;
  walls.walls = valid(msg->walls);
  walls.seen_over = valid(msg->seen_over);
  const auto outcome = session_->addWalls(msg->keyframe_id, walls);
  if (outcome == BackendSession::Outcome::kAdded || outcome == BackendSession::Outcome::kBuffered) {
    journal_->record(kWallsChannel, *msg);
  }
  if (outcome == BackendSession::Outcome::kDropped) {
    warnings_.warn("wall observations", "walls of a keyframe that never arrived, dropped");
  } else if (outcome == BackendSession::Outcome::kAdded && !walls.walls.empty()) {
    changed_ = true;
  }
}

void BackendNode::roomsCallback(const tacs_graphs::RoomObservations::ConstPtr& msg) {
  journal_->record(kRoomsChannel, *msg);
  // Rooms arrive associated (room merging runs in room_segmentation) with the backend's wall ids.
  if (msg->complete_set) {
    std::set<uint32_t> ids;
    for (const auto& r : msg->rooms) ids.insert(r.room_id);
    changed_ = session_->retainRooms(ids) > 0 || changed_;
  }
  for (const auto& r : msg->rooms) {
    changed_ = changed_ || !r.absorbed_room_ids.empty();
    if (session_->takeRoom(fromRoomObservationMsg(r),
                           {r.absorbed_room_ids.begin(), r.absorbed_room_ids.end()},
                           wallToWallPairs(r))) {
      changed_ = true;
    } else {
      warnings_.warn("room observation", "no facing wall pair in the graph, room not updated");
    }
  }
}

void BackendNode::loopCallback(const tacs_graphs::LoopClosure::ConstPtr& msg) {
  const LoopEdge edge = fromLoopClosureMsg(*msg);
  const Matrix6d information = fromMatrixArray(msg->information);
  if (!edge.position.allFinite() || !information.allFinite()) {
    warnings_.warn("loop closure", "non-finite relative pose or information, skipped");
    return;
  }
  const auto outcome = session_->addLoop(edge, information);
  if (outcome == BackendSession::Outcome::kDuplicate) return;  // republished after a restart
  journal_->record(kLoopsChannel, *msg);
  if (outcome == BackendSession::Outcome::kAdded) changed_ = true;
}

void BackendNode::publishIfChanged() {
  if (!changed_) return;
  changed_ = false;
  update();
}

void BackendNode::update() {
  session_->optimizeIfDue();
  const SceneGraph graph = session_->sceneGraph();
  const std::string& map = config_.frames.map_frame;
  graph_pub_.publish(toSceneGraphMsg(graph, session_->wallObservationCounts(), map, latest_stamp_));
  marker_pub_.publish(sceneGraphMarkers(graph, map, latest_stamp_));
  if (prior_) relocalize(graph);
}

void BackendNode::relocalize(const SceneGraph& graph) {
  const bool was_placed = prior_->localized();
  const Pose3 place = prior_->T_prior_session();
  const size_t pairs = prior_->roomPairs().size();
  prior_->update(graph, session_->keyframeClouds(), latest_stamp_, drivenDistance(graph));
  if (!prior_->localized()) return;
  if (!was_placed) {
    const auto first = prior_->localizationJson()["first_localization"];
    ROS_INFO_STREAM("Localized in the prior map after "
                    << first["distance_m"].get<double>() << " m: "
                    << (first["session_room"].is_null() ? std::string("the whole map")
                                                        : "room " + first["session_room"].dump())
                    << " in prior room " << first["prior_room"] << " (score "
                    << first["score"].get<double>() << ")");
  }
  if (!was_placed || !place.isApprox(prior_->T_prior_session()) ||
      pairs != prior_->roomPairs().size()) {
    prior_marker_pub_.publish(
        priorMapMarkers(prior_->prior().graph, prior_->roomPairs(), "prior_map", latest_stamp_));
  }
}

bool BackendNode::loadPrior(std::string* message) {
  const std::string dir = pnh_.param<std::string>("prior_map", "");
  const PriorMode mode =
      pnh_.param("localize_only", false) ? PriorMode::kLocalizeOnly : PriorMode::kMerge;
  try {
    if (dir.empty()) throw std::runtime_error("~prior_map is empty");
    prior_ = std::make_unique<PriorSession>(PriorMap::load(dir), mode, config_.relocalization);
    *message = "prior map " + dir + ": " + std::to_string(prior_->prior().graph.rooms.size()) +
               " rooms, " + std::to_string(prior_->prior().points.size()) + " points (" +
               enumName(mode) + ")";
    ROS_INFO_STREAM(*message);
    if (session_->keyframeCount() > 0) relocalize(session_->sceneGraph());
    return true;
  } catch (const std::exception& e) {
    *message = std::string("prior map not loaded: ") + e.what();
    ROS_ERROR_STREAM(*message);
    return false;
  }
}

bool BackendNode::loadPriorService(std_srvs::Trigger::Request&, std_srvs::Trigger::Response& res) {
  res.success = loadPrior(&res.message);
  return true;
}

void BackendNode::publishTf(const ros::TimerEvent&) {
  // Stamped slightly ahead, as usual for map -> odom, so that lookups at the newest odometry
  // time succeed between two broadcasts.
  const double stamp = (ros::Time::now() + ros::Duration(0.1)).toSec();
  // A paused (simulated) clock fires the timer at one time again: tf2 would reject the repeat.
  if (stamp <= last_tf_stamp_) return;
  last_tf_stamp_ = stamp;
  tf_broadcaster_.sendTransform(toTransformMsg(session_->mapToOdom(), config_.frames.map_frame,
                                               config_.frames.odom_frame, stamp));
  if (prior_ && prior_->localized()) {
    tf_broadcaster_.sendTransform(
        toTransformMsg(prior_->T_prior_session(), "prior_map", config_.frames.map_frame, stamp));
  }
}

void BackendNode::publishMap(const ros::TimerEvent&) {
  if (!map_dirty_ || map_pub_.getNumSubscribers() == 0) return;
  map_dirty_ = false;
  map_pub_.publish(toRosCloud(session_->mapCloud(config_.map_export.cloud_voxel_m),
                              config_.frames.map_frame, latest_stamp_));
}

bool BackendNode::save(std::string* message) {
  try {
    session_->save(output_dir_, config_.map_export);
    *message =
        "saved " + std::to_string(session_->keyframeCount()) + " keyframes to " + output_dir_;
    if (prior_) {
      writeFileAtomically(output_dir_ + "/localization.json",
                          prior_->localizationJson().dump(2) + "\n");
      // The folder itself stays in the session's frame (its journal is); the session in the
      // prior's frame, merged into it, goes beside it as the prior map of the next run.
      const double voxel_m = config_.map_export.cloud_voxel_m;
      const std::string in_prior = output_dir_ + "/" + kPriorFrameFolder;
      if (prior_->writePriorFrameMap(in_prior, session_->sceneGraph(), session_->mapCloud(voxel_m),
                                     voxel_m)) {
        *message += "; in the prior's frame to " + in_prior;
      }
    }
    ROS_INFO_STREAM(*message);
    const auto& input = session_->scanInput();
    if (input && input->dropRatio() > kUnreliableDropRatio) {
      ROS_WARN_STREAM("the saved graph was built from "
                      << input->scans_received << " of "
                      << input->scans_received + input->scans_missing << " scans ("
                      << static_cast<int>(std::lround(100.0 * input->dropRatio()))
                      << " % dropped while the odometry fell behind): fewer scans than the "
                         "sensor gave; replay the bag with play_bag for the full map");
    }
    return true;
  } catch (const std::exception& e) {
    *message = std::string("save failed: ") + e.what();
    ROS_ERROR_STREAM(*message);
    return false;
  }
}

bool BackendNode::saveService(std_srvs::Trigger::Request&, std_srvs::Trigger::Response& res) {
  publishIfChanged();  // messages of the same batch as the request are in the saved graph
  res.success = save(&res.message);
  return true;
}

void BackendNode::shutdown() {
  if (!save_on_shutdown_ || session_->keyframeCount() == 0) return;
  session_->optimize();
  std::string message;
  save(&message);
}

}  // namespace tacs
