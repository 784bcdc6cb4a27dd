#include "tacs_graphs/relocalization/prior_map.h"

#include <pcl/PCLPointCloud2.h>
#include <pcl/common/io.h>
#include <pcl/io/pcd_io.h>

#include <cmath>
#include <filesystem>

namespace tacs {

namespace {

std::string requireFile(const std::string& dir, const std::string& name) {
  const std::string path = dir + "/" + name;
  if (!std::filesystem::is_regular_file(path)) {
    throw PriorMapError(path +
                        ": missing (a prior map is a run folder of tacs_offline or of "
                        "the backend node's save)");
  }
  return path;
}

/// The header is checked before PCL reads the data: its reader trusts the header and can crash
/// on a file cut short or on one that is no PCD at all.
PointCloud readPcd(const std::string& path) {
  const auto fail = [&](const std::string& why) -> PriorMapError {
    return PriorMapError(path + ": not a readable PCD point cloud (" + why + ")");
  };
  pcl::PCDReader reader;
  pcl::PCLPointCloud2 header;
  Eigen::Vector4f origin;
  Eigen::Quaternionf orientation;
  int version = 0, data_type = 0;
  unsigned int data_index = 0;
  if (reader.readHeader(path, header, origin, orientation, version, data_type, data_index) != 0) {
    throw fail("bad header");
  }
  for (const char* name : {"x", "y", "z"}) {
    if (pcl::getFieldIndex(header, name) < 0) throw fail(std::string("no field ") + name);
  }
  const uint64_t points = static_cast<uint64_t>(header.width) * header.height;
  if (points == 0) throw fail("no points");
  const uint64_t size = std::filesystem::file_size(path);
  if (data_type == 1 && size < data_index + points * header.point_step) throw fail("cut short");
  if (data_type == 2 && size < data_index + 8) throw fail("cut short");
  PointCloud cloud;
  if (reader.read(path, cloud) != 0) throw fail("bad data");
  return cloud;
}

}  // namespace

PriorMap PriorMap::load(const std::string& dir) {
  if (!std::filesystem::is_directory(dir)) throw PriorMapError(dir + ": no such folder");
  PriorMap prior;
  prior.dir = dir;
  const std::string graph_path = requireFile(dir, "scene_graph.json");
  try {
    prior.graph = SceneGraph::load(graph_path);
  } catch (const std::exception& e) {
    throw PriorMapError(e.what());  // SceneGraph::load names the file and the bad field
  }
  if (prior.graph.rooms.empty()) {
    throw PriorMapError(graph_path + ": the graph has no room to relocalize by");
  }
  const std::string cloud_path = requireFile(dir, "map.pcd");
  const PointCloud cloud = readPcd(cloud_path);
  prior.points.reserve(cloud.size());
  for (const auto& p : cloud.points) {
    if (std::isfinite(p.x) && std::isfinite(p.y) && std::isfinite(p.z)) prior.points.push_back(p);
  }
  if (prior.points.empty()) throw PriorMapError(cloud_path + ": no finite point");
  return prior;
}

}  // namespace tacs
