#include "tacs_graphs/pipeline/keyframe_stages.h"

#include <pcl/common/transforms.h>

namespace tacs {

LevelledKeyframe GroundLeveller::level(const PointCloud::ConstPtr& cloud_in_base,
                                       const Pose3& T_map_base) {
  LevelledKeyframe out;
  if (!enabled_) {
    out.cloud_in_ground = cloud_in_base;
    return out;
  }
  out.levelled = true;
  out.T_base_ground = tracker_.next(*cloud_in_base, T_map_base).T_base_floor;
  PointCloud::Ptr in_ground(new PointCloud);
  pcl::transformPointCloud(*cloud_in_base, *in_ground,
                           out.T_base_ground.inverse().matrix().cast<float>());
  out.cloud_in_ground = in_ground;
  return out;
}

WallExtractionResult extractKeyframeWalls(const WallExtractor& extractor,
                                          const LevelledKeyframe& keyframe,
                                          const Eigen::Vector3d& sensor_in_base) {
  if (!keyframe.levelled) return extractor.extract(*keyframe.cloud_in_ground, sensor_in_base);
  return extractor.extractInFrame(*keyframe.cloud_in_ground, keyframe.T_base_ground,
                                  sensor_in_base);
}

TraversabilityResult keyframeTraversability(const TraversabilityMapper& mapper,
                                            const LevelledKeyframe& keyframe) {
  return mapper.process(*keyframe.cloud_in_ground);
}

}  // namespace tacs
