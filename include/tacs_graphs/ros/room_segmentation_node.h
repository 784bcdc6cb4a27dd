// The room_segmentation node: traversable graphs (and, for the voxel baseline, keyframe clouds)
// plus the backend's scene graph (optimised poses, wall landmarks) -> RoomSegmenter (paper
// Sec. III-B, III-C) -> /tacs/room_observations: per keyframe that changed rooms, every updated
// mapped room with its id, kind, walls, centre, free space, keyframes, whether it was a
// re-detection and the wall-to-wall edges of its merging (the backend draws the rooms).
//
// Parameters: the pipeline configuration under ~config_ns (default /tacs; sections frames,
// traversability, walls and rooms), and private ones:
//   ~max_wait_keyframes (5)     keyframes a keyframe waits for the backend's pose at most
//   ~repose_distance_m (0.05)   [m] optimised keyframes moved this far re-pose the traversable map
//   ~repose_angle_deg (1.0)     [deg] or turned this much
//   ~journal_dir (""), ~replay_journal (auto): crash journal of the inputs (message_journal.h).
//     A respawned node replays its traversable graphs, segments them once the backend's latched
//     scene graph is in, sends all its rooms (complete_set) and asks for the graphs it missed.
// On a tacs_graphs/Resync from another node it sends all its rooms again (complete_set).
#pragma once

#include <ros/ros.h>
#include <tacs_graphs/Keyframe.h>
#include <tacs_graphs/Resync.h>
#include <tacs_graphs/SceneGraph.h>
#include <tacs_graphs/TraversableGraph.h>

#include <memory>

#include "tacs_graphs/pipeline/pipeline_config.h"
#include "tacs_graphs/pipeline/room_segmentation_session.h"
#include "tacs_graphs/ros/message_journal.h"
#include "tacs_graphs/ros/warn_once.h"

namespace tacs {

class RoomSegmentationNode {
 public:
  /// Throws ConfigError on a bad configuration.
  RoomSegmentationNode(ros::NodeHandle& nh, ros::NodeHandle& pnh);

  /// Publishes what the room segmenter still accumulates (the last region) and logs a summary.
  void shutdown();

 private:
  void graphCallback(const tacs_graphs::TraversableGraph::ConstPtr& msg);
  void keyframeCallback(const tacs_graphs::Keyframe::ConstPtr& msg);
  void sceneGraphCallback(const tacs_graphs::SceneGraph::ConstPtr& msg);
  void resyncCallback(const tacs_graphs::Resync::ConstPtr& msg);
  void processReady();
  void publish(const RoomUpdate& update);
  /// All mapped rooms in one message marked complete_set (none marked as a re-detection).
  void publishCompleteSet();
  void replayJournal(ros::NodeHandle& nh);

  PipelineConfig config_;
  std::unique_ptr<RoomSegmentationSession> session_;
  std::unique_ptr<NodeJournal> journal_;
  ros::Subscriber graph_sub_, keyframe_sub_, scene_graph_sub_, resync_sub_;
  ros::Publisher rooms_pub_, resync_pub_;
  int64_t newest_input_id_ = -1;
  bool complete_set_due_ = false;  // after a replay, once the first scene graph is in
  WarnOnce warnings_;
  size_t published_ = 0;
  size_t redetections_ = 0;
};

}  // namespace tacs
