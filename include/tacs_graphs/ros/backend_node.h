// The backend node: keyframes, wall observations, room observations and loop closures ->
// Backend (the single owner of the scene graph) -> /tacs/scene_graph, TF map -> odom,
// /tacs/markers, /tacs/map_points; service ~save writes scene_graph.json, map.bt, map.pcd (and
// the measurement journal) into ~output_dir, as does a shutdown. The OctoMap of a long run takes
// a while to ray-cast: call ~save before stopping, or give roslaunch a longer --sigint-timeout.
//
// Private parameters:
//   ~config_ns (/tacs)              pipeline configuration (frames, walls, backend, map_export)
// Room observations carry mapped rooms (room merging runs in room_segmentation): they go to
// Backend::setRoom with their wall-to-wall edges (paper eq. 4).
//   ~output_dir ($ROS_HOME/tacs_graphs)  where ~save and the shutdown write
//   ~save_on_shutdown (true)
//   ~recover (false)                replay ~output_dir/backend_journal.json at start
//   ~map_publish_period_s (5.0)     /tacs/map_points period (only while subscribed)
//   ~tf_rate_hz (20.0)              map -> odom broadcast rate
//   ~journal_dir ("")               crash journal folder (message_journal.h); the launch files
//                                   give output_dir/journal and respawn the node
//   ~replay_journal (auto)          replay the journal at start: auto (after a respawn), true,
//   false
//   ~prior_map ("")                 a run folder to relocalize in (docs/DESIGN.md "Prior maps");
//   ~localize_only (false)          its mode; service ~load_prior (re)reads both parameters.
//                                   Once placed: TF prior_map -> map, /tacs/prior_markers (the
//                                   prior's graph, its re-observed rooms as green pillars), and
//                                   ~save adds localization.json (the saved map stays in the
//                                   session's own frame; tacs_offline --prior writes the merge).
// After a replay it publishes a latched tacs_graphs/Resync on /tacs/resync: the odometry resends
// the keyframes the backend missed while it was down, room_segmentation and loop_closure send
// their rooms and loops again (duplicates are recognised and dropped).
#pragma once

#include <ros/ros.h>
#include <std_srvs/Trigger.h>
#include <tacs_graphs/Keyframe.h>
#include <tacs_graphs/LoopClosure.h>
#include <tacs_graphs/RoomObservations.h>
#include <tacs_graphs/WallObservations.h>
#include <tf2_ros/transform_broadcaster.h>

#include <memory>
#include <optional>
#include <string>

#include "tacs_graphs/backend/map_export.h"
#include "tacs_graphs/pipeline/backend_session.h"
#include "tacs_graphs/pipeline/pipeline_config.h"
#include "tacs_graphs/relocalization/prior_session.h"
#include "tacs_graphs/ros/message_journal.h"
#include "tacs_graphs/ros/warn_once.h"

namespace tacs {

class BackendNode {
 public:
  /// Throws ConfigError on a bad configuration.
  BackendNode(ros::NodeHandle& nh, ros::NodeHandle& pnh);

  /// Writes the run products if ~save_on_shutdown; logs instead of throwing.
  void shutdown();

  /// Optimises if due and publishes, once for all the messages taken since the last call: the
  /// main loop calls it after each batch of callbacks, so a backlog of keyframes (a bag played
  /// fast, a long optimisation) costs one optimisation and one scene graph, not one per message.
  void publishIfChanged();

 private:
  void keyframeCallback(const tacs_graphs::Keyframe::ConstPtr& msg);
  void wallsCallback(const tacs_graphs::WallObservations::ConstPtr& msg);
  void roomsCallback(const tacs_graphs::RoomObservations::ConstPtr& msg);
  void loopCallback(const tacs_graphs::LoopClosure::ConstPtr& msg);
  bool saveService(std_srvs::Trigger::Request& req, std_srvs::Trigger::Response& res);
  void publishTf(const ros::TimerEvent&);
  void publishMap(const ros::TimerEvent&);
  /// Optimises if due and publishes the scene graph and markers.
  void update();
  bool save(std::string* message);
  /// Reads ~prior_map and ~localize_only and loads the prior; false (and why) when it cannot.
  bool loadPrior(std::string* message);
  bool loadPriorService(std_srvs::Trigger::Request& req, std_srvs::Trigger::Response& res);
  /// Hands the graph to the prior session; publishes the prior's markers when its place moved.
  void relocalize(const SceneGraph& graph);
  /// Rebuilds the session from the crash journal and asks the others to resend what it lacks.
  void replayJournal();

  PipelineConfig config_;
  std::string output_dir_;
  bool save_on_shutdown_ = true;
  std::unique_ptr<BackendSession> session_;
  std::unique_ptr<NodeJournal> journal_;
  double latest_stamp_ = 0.0;
  double last_tf_stamp_ = 0.0;
  bool map_dirty_ = false;
  bool changed_ = false;                 // messages taken since the last publishIfChanged()
  std::optional<uint32_t> resync_from_;  // the first keyframe asked for again after a restart

  ros::Subscriber keyframe_sub_, walls_sub_, rooms_sub_, loop_sub_;
  ros::Publisher graph_pub_, marker_pub_, map_pub_, resync_pub_;
  ros::ServiceServer save_srv_;
  ros::Timer tf_timer_, map_timer_;
  tf2_ros::TransformBroadcaster tf_broadcaster_;
  ros::NodeHandle pnh_;
  std::unique_ptr<PriorSession> prior_;
  ros::Publisher prior_marker_pub_;
  ros::ServiceServer load_prior_srv_;
  WarnOnce warnings_;
};

}  // namespace tacs
