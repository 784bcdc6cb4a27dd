#include "tacs_graphs/sim/ground_truth.h"

#include <fstream>

namespace tacs::sim {
namespace {

constexpr const char* kFormat = "tacs_graphs/ground_truth";

nlohmann::json xy(const Eigen::Vector2d& p) { return {p.x(), p.y()}; }

}  // namespace

GroundTruth groundTruthOf(const World& world) {
  return GroundTruth{world.name, world.rooms, world.walls};
}

nlohmann::json groundTruthToJson(const GroundTruth& gt) {
  nlohmann::json j = {{"format", kFormat}, {"version", 1}, {"world", gt.world_name}};
  j["rooms"] = nlohmann::json::array();
  for (const auto& room : gt.rooms) {
    nlohmann::json poly = nlohmann::json::array();
    for (const auto& p : room.polygon) poly.push_back(xy(p));
    j["rooms"].push_back({{"id", room.id}, {"kind", room.kind}, {"polygon", poly}});
  }
  j["walls"] = nlohmann::json::array();
  for (const auto& w : gt.walls) {
    j["walls"].push_back({{"from", xy(w.from)},
                          {"to", xy(w.to)},
                          {"z_min", w.z_min},
                          {"z_max", w.z_max},
                          {"thickness", w.thickness}});
  }
  return j;
}

GroundTruth groundTruthFromJson(const nlohmann::json& j, const std::string& name) {
  if (!j.is_object() || j.value("format", "") != kFormat) {
    throw WorldError(name + ": format: expected \"" + std::string(kFormat) + "\"");
  }
  if (j.value("version", 0) != 1) throw WorldError(name + ": version: expected 1");
  // Rooms and walls use the world syntax: reuse the world parser on a minimal world.
  nlohmann::json world = {{"rooms", j.value("rooms", nlohmann::json::array())},
                          {"walls", j.value("walls", nlohmann::json::array())},
                          {"floors", {{{"polygon", {{0, 0}, {1, 0}, {0, 1}}}, {"z", 0}}}},
                          {"trajectory", {{"waypoints", {{0, 0}, {1, 0}}}}}};
  const World w = parseWorld(world, name);
  return GroundTruth{j.value("world", ""), w.rooms, w.walls};
}

void writeGroundTruth(const std::string& path, const GroundTruth& gt) {
  std::ofstream out(path);
  out << groundTruthToJson(gt).dump(1) << "\n";
  if (!out) throw WorldError(path + ": cannot write file");
}

GroundTruth readGroundTruth(const std::string& path) {
  return groundTruthFromJson(readJsonFile(path), path);
}

}  // namespace tacs::sim
