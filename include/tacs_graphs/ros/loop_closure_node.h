// The loop_closure node: keyframes (clouds), the backend's scene graph (pose estimates) and room
// observations -> LoopClosureSession (LoopDetector) -> /tacs/loop_closures.
//
// loop_closure.method "cosg" (paper Sec. III-D, CoSG-LCD): a room observation marked as a
// re-detection searches that room's keyframes for a loop with the observation's query keyframe
// (a request waits for the query keyframe's cloud if it is not in yet). "distance" (baseline):
// every new keyframe searches the keyframes within the distance threshold. Pose estimates follow
// the scene graph (LoopDetector::updatePoses); keyframes not yet optimised are placed with the
// latest map -> odom correction. At shutdown the node logs the detection totals and t_LD.
//
// Parameters: the pipeline configuration under ~config_ns (default /tacs; sections frames,
// odometry (its voxel grid for the stored clouds) and loop_closure), and private ones:
//   ~journal_dir (""), ~replay_journal (auto): crash journal (message_journal.h) of the keyframes
//     and of the loops found. A respawned node takes its keyframes back (no detection is re-run),
//     then asks for the keyframes it missed.
// On a tacs_graphs/Resync it sends every loop it found again (the backend drops the ones it has).
#pragma once

#include <ros/ros.h>
#include <tacs_graphs/Keyframe.h>
#include <tacs_graphs/LoopClosure.h>
#include <tacs_graphs/Resync.h>
#include <tacs_graphs/RoomObservations.h>
#include <tacs_graphs/SceneGraph.h>

#include <memory>
#include <vector>

#include "tacs_graphs/pipeline/loop_closure_session.h"
#include "tacs_graphs/pipeline/pipeline_config.h"
#include "tacs_graphs/ros/message_journal.h"
#include "tacs_graphs/ros/warn_once.h"

namespace tacs {

class LoopClosureNode {
 public:
  /// Throws ConfigError on a bad configuration.
  LoopClosureNode(ros::NodeHandle& nh, ros::NodeHandle& pnh);

  /// Logs the detection totals (t_LD).
  void shutdown();

 private:
  void keyframeCallback(const tacs_graphs::Keyframe::ConstPtr& msg);
  void sceneGraphCallback(const tacs_graphs::SceneGraph::ConstPtr& msg);
  void roomsCallback(const tacs_graphs::RoomObservations::ConstPtr& msg);
  void resyncCallback(const tacs_graphs::Resync::ConstPtr& msg);
  void replayJournal(ros::NodeHandle& nh);
  void publish(const std::vector<RoomLoopDetection>& detections);

  PipelineConfig config_;
  LoopClosureSession session_;
  std::unique_ptr<NodeJournal> journal_;
  std::vector<tacs_graphs::LoopClosure> loops_sent_;
  ros::Subscriber keyframe_sub_, scene_graph_sub_, rooms_sub_, resync_sub_;
  ros::Publisher loop_pub_, resync_pub_;
  WarnOnce warnings_;
  double latest_stamp_ = 0.0;
  uint32_t newest_id_ = 0;
  size_t published_ = 0;
};

}  // namespace tacs
