// A simulated world: plain data read from the JSON world format of docs/DESIGN.md ("The simulated
// worlds"). Every length is in metres, every angle in degrees as in the file.
#pragma once

#include <Eigen/Core>
#include <cstdint>
#include <nlohmann/json.hpp>
#include <stdexcept>
#include <string>
#include <vector>

namespace tacs::sim {

/// A malformed world file. what() is "<file>: <json.path>: <reason>", e.g.
/// "corridor.json: walls[3].to: expected [x, y]".
class WorldError : public std::runtime_error {
 public:
  using std::runtime_error::runtime_error;
};

using Polygon2 = std::vector<Eigen::Vector2d>;

/// A vertical slab between two floor points; both faces are surfaces.
struct Wall {
  Eigen::Vector2d from = Eigen::Vector2d::Zero();
  Eigen::Vector2d to = Eigen::Vector2d::Zero();
  double z_min = 0.0;         // [m]
  double z_max = 2.8;         // [m]; a half wall has a low z_max, a rail a raised z_min
  double thickness = 0.15;    // [m]
  double reflectivity = 0.6;  // [0..1], scales the simulated intensity
};

/// A box standing on its own, rotated about z (furniture, cabinets, pipes, stairs).
struct Box {
  Eigen::Vector3d center = Eigen::Vector3d::Zero();
  Eigen::Vector3d size = Eigen::Vector3d::Ones();  // full extents [m]
  double yaw_deg = 0.0;
  double reflectivity = 0.7;
};

/// A horizontal polygon (floor or ceiling) at height z.
struct HorizontalPolygon {
  Polygon2 polygon;
  double z = 0.0;
  double reflectivity = 0.3;
};

/// Ground truth: the free-space region of one room or corridor.
struct Room {
  std::string id;
  std::string kind = "room";  // "room" or "corridor"
  Polygon2 polygon;
};

struct TrajectorySpec {
  /// Waypoint x, y and z; z is NaN for [x, y] waypoints (robot on the floor under it).
  std::vector<Eigen::Vector3d> waypoints;
  double speed_mps = 0.8;
  int laps = 1;                     // > 1: drive back to the first waypoint and repeat
  double corner_radius_m = 0.5;     // half-width of the path smoothing window at corners
  double max_yaw_rate_dps = 45.0;   // the robot slows down in turns (turns in place at U-turns)
  double max_accel_mps2 = 0.5;      // starts and stops at rest
  double max_yaw_accel_dps2 = 0.0;  // the yaw rate changes by at most this per second (0: at
                                    // once, as the first worlds were made)
  double jitter_deg = 0.3;          // amplitude of the roll/pitch vibration of a ground robot
  double jitter_z_m = 0.004;        // amplitude of the vertical vibration
};

struct SensorSpec {
  std::string model = "vlp16";  // vlp16, os1_64, os0_128 or custom
  int rings = 16;
  double vfov_deg = 30.0;  // full vertical field of view, symmetric about the horizon
  double hres_deg = 0.2;   // horizontal step between firings
  double max_range_m = 100.0;
  double min_range_m = 0.4;
  double rate_hz = 10.0;
  double mount_height_m = 0.5;  // sensor origin above base_link (on the floor)
  double range_noise_std_m = 0.01;
  double dropout_prob = 0.005;     // share of returns lost at random
  double intensity_noise = 2.0;    // std of additive intensity noise [intensity units]
  bool motion_distortion = false;  // cast each firing from the pose at its own time
  // Per-point time convention of the clouds: "time" (Velodyne: float32 s since the sweep
  // start) or "t" (Ouster: uint32 ns since the sweep start). Presets: vlp16 time, os* t.
  std::string time_field = "time";
  uint64_t seed = 1;
};

struct World {
  std::string name;
  std::vector<Wall> walls;
  std::vector<Box> boxes;
  std::vector<HorizontalPolygon> floors;
  std::vector<HorizontalPolygon> ceilings;
  std::vector<Room> rooms;
  TrajectorySpec trajectory;
  SensorSpec sensor;
};

/// Fills rings, vfov, hres and ranges of a named model (vlp16, os1_64, os0_128). Returns false
/// for an unknown name.
bool applySensorPreset(const std::string& model, SensorSpec* sensor);

/// Parses a world; `name` (usually the file path) prefixes every error message.
World parseWorld(const nlohmann::json& j, const std::string& name);

/// Reads a JSON file. Throws WorldError "<path>: cannot open file" or "<path>: invalid JSON ...".
nlohmann::json readJsonFile(const std::string& path);

/// Reads and parses a world file. Throws WorldError.
World loadWorld(const std::string& path);

/// Even-odd point-in-polygon test.
bool pointInPolygon(const Polygon2& polygon, const Eigen::Vector2d& p);

/// Signed area (positive counter-clockwise).
double polygonArea(const Polygon2& polygon);

}  // namespace tacs::sim
