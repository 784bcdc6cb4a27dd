// ground_truth.json: the rooms (free-space polygons) and walls of a simulated world, written
// beside the bag and read back by the evaluation.
//   {"format": "tacs_graphs/ground_truth", "version": 1,
//    "rooms": [{"id", "kind", "polygon": [[x, y], ...]}],
//    "walls": [{"from": [x, y], "to": [x, y], "z_min", "z_max", "thickness"}]}
#pragma once

#include <nlohmann/json.hpp>
#include <string>
#include <vector>

#include "tacs_graphs/sim/world.h"

namespace tacs::sim {

struct GroundTruth {
  std::string world_name;
  std::vector<Room> rooms;
  std::vector<Wall> walls;
};

GroundTruth groundTruthOf(const World& world);

nlohmann::json groundTruthToJson(const GroundTruth& gt);

/// Throws WorldError "<name>: <json.path>: <reason>".
GroundTruth groundTruthFromJson(const nlohmann::json& j, const std::string& name);

void writeGroundTruth(const std::string& path, const GroundTruth& gt);
GroundTruth readGroundTruth(const std::string& path);

}  // namespace tacs::sim
