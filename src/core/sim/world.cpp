#include "tacs_graphs/sim/world.h"

#include <cmath>
#include <fstream>
#include <limits>
#include <set>

namespace tacs::sim {
namespace {

using nlohmann::json;

/// Typed access to one JSON object with the error path of each field; rejects unknown keys
/// (a typo such as "tickness" would otherwise silently keep the default).
class ObjectReader {
 public:
  ObjectReader(const json& j, std::string path, const std::string& file)
      : j_(j), path_(std::move(path)), file_(file) {
    if (!j_.is_object()) fail(path_, "expected an object");
  }
  ~ObjectReader() noexcept(false) {
    if (std::uncaught_exceptions() > 0) return;
    for (const auto& item : j_.items()) {
      if (!claimed_.count(item.key())) fail(sub(item.key()), "unknown key");
    }
  }

  [[noreturn]] void fail(const std::string& path, const std::string& reason) const {
    throw WorldError(file_ + ": " + (path.empty() ? std::string("top level") : path) + ": " +
                     reason);
  }
  std::string sub(const std::string& key) const { return path_.empty() ? key : path_ + "." + key; }
  const std::string& file() const { return file_; }

  /// The value of `key`, or nullptr when absent (and not required).
  const json* get(const std::string& key, bool required) {
    claimed_.insert(key);
    if (!j_.contains(key)) {
      if (required) fail(sub(key), "missing");
      return nullptr;
    }
    return &j_.at(key);
  }

  void number(const std::string& key, double* out, bool required = false) {
    if (const json* v = get(key, required)) *out = toNumber(*v, sub(key));
  }
  void positive(const std::string& key, double* out, bool required = false) {
    number(key, out, required);
    if (!(*out > 0.0)) fail(sub(key), "must be > 0");
  }
  void unit(const std::string& key, double* out) {
    number(key, out);
    if (*out < 0.0 || *out > 1.0) fail(sub(key), "must be in [0, 1]");
  }
  void integer(const std::string& key, int* out, int min_value) {
    if (const json* v = get(key, false)) {
      if (!v->is_number_integer()) fail(sub(key), "expected an integer");
      *out = v->get<int>();
      if (*out < min_value) fail(sub(key), "must be >= " + std::to_string(min_value));
    }
  }
  void boolean(const std::string& key, bool* out) {
    if (const json* v = get(key, false)) {
      if (!v->is_boolean()) fail(sub(key), "expected true or false");
      *out = v->get<bool>();
    }
  }
  void string(const std::string& key, std::string* out, bool required = false) {
    if (const json* v = get(key, required)) {
      if (!v->is_string()) fail(sub(key), "expected a string");
      *out = v->get<std::string>();
    }
  }

  double toNumber(const json& v, const std::string& path) const {
    if (!v.is_number()) fail(path, "expected a number");
    const double d = v.get<double>();
    if (!std::isfinite(d)) fail(path, "expected a finite number");
    return d;
  }
  /// [x, y] (dims 2), [x, y, z] (dims 3) or either (dims 0: z NaN when absent).
  Eigen::Vector3d point(const json& v, const std::string& path, int dims) const {
    const char* expected = dims == 3   ? "expected [x, y, z]"
                           : dims == 2 ? "expected [x, y]"
                                       : "expected [x, y] or [x, y, z]";
    const size_t n = v.is_array() ? v.size() : 0;
    if (!(dims == 0 ? (n == 2 || n == 3) : n == static_cast<size_t>(dims))) fail(path, expected);
    Eigen::Vector3d p(0, 0, std::numeric_limits<double>::quiet_NaN());
    for (size_t i = 0; i < n; ++i) {
      if (!v[i].is_number()) fail(path, expected);
      p[i] = toNumber(v[i], path);
    }
    return p;
  }
  Eigen::Vector2d point2(const std::string& key) {
    return point(*get(key, true), sub(key), 2).head<2>();
  }
  Polygon2 polygon(const std::string& key) {
    const json& v = *get(key, true);
    const std::string path = sub(key);
    if (!v.is_array() || v.size() < 3) fail(path, "expected a list of at least 3 [x, y] points");
    Polygon2 poly;
    for (size_t i = 0; i < v.size(); ++i) {
      poly.push_back(point(v[i], path + "[" + std::to_string(i) + "]", 2).head<2>());
    }
    if (std::abs(polygonArea(poly)) < 1e-9) fail(path, "polygon has zero area");
    return poly;
  }

 private:
  const json& j_;
  std::string path_;
  const std::string& file_;
  std::set<std::string> claimed_;
};

/// Calls fn(element, "key[i]") for every element of the optional array `key`.
template <class Fn>
void forEach(ObjectReader& r, const std::string& key, Fn fn) {
  const json* v = r.get(key, false);
  if (!v) return;
  if (!v->is_array()) r.fail(r.sub(key), "expected a list");
  for (size_t i = 0; i < v->size(); ++i) fn((*v)[i], r.sub(key) + "[" + std::to_string(i) + "]");
}

void parseHorizontal(ObjectReader& top, const std::string& key, double default_refl,
                     std::vector<HorizontalPolygon>* out) {
  forEach(top, key, [&](const json& e, const std::string& path) {
    ObjectReader r(e, path, top.file());
    HorizontalPolygon h;
    h.reflectivity = default_refl;
    h.polygon = r.polygon("polygon");
    r.number("z", &h.z, true);
    r.unit("reflectivity", &h.reflectivity);
    out->push_back(h);
  });
}

void parseTrajectory(ObjectReader& top, TrajectorySpec* t) {
  const json* v = top.get("trajectory", true);
  ObjectReader r(*v, "trajectory", top.file());
  const json* wps = r.get("waypoints", true);
  if (!wps->is_array() || wps->size() < 2) {
    r.fail("trajectory.waypoints", "expected a list of at least 2 waypoints");
  }
  for (size_t i = 0; i < wps->size(); ++i) {
    t->waypoints.push_back(
        r.point((*wps)[i], "trajectory.waypoints[" + std::to_string(i) + "]", 0));
  }
  r.positive("speed_mps", &t->speed_mps);
  r.integer("laps", &t->laps, 1);
  r.number("corner_radius_m", &t->corner_radius_m);
  if (t->corner_radius_m < 0) r.fail("trajectory.corner_radius_m", "must be >= 0");
  r.positive("max_yaw_rate_dps", &t->max_yaw_rate_dps);
  r.positive("max_accel_mps2", &t->max_accel_mps2);
  r.number("max_yaw_accel_dps2", &t->max_yaw_accel_dps2);
  if (t->max_yaw_accel_dps2 < 0) r.fail("trajectory.max_yaw_accel_dps2", "must be >= 0 (0: none)");
  r.number("jitter_deg", &t->jitter_deg);
  r.number("jitter_z_m", &t->jitter_z_m);
  if (t->jitter_deg < 0 || t->jitter_deg > 10)
    r.fail("trajectory.jitter_deg", "must be in [0, 10]");
  if (t->jitter_z_m < 0 || t->jitter_z_m > 0.5) {
    r.fail("trajectory.jitter_z_m", "must be in [0, 0.5]");
  }
}

void parseSensor(ObjectReader& top, SensorSpec* s) {
  const json* v = top.get("sensor", false);
  if (!v) return;
  ObjectReader r(*v, "sensor", top.file());
  r.string("model", &s->model);
  if (s->model != "custom" && !applySensorPreset(s->model, s)) {
    r.fail("sensor.model", "unknown model '" + s->model + "' (vlp16, os1_64, os0_128, custom)");
  }
  r.integer("rings", &s->rings, 1);
  r.positive("vfov_deg", &s->vfov_deg);
  if (s->vfov_deg >= 180.0) r.fail("sensor.vfov_deg", "must be < 180");
  r.positive("hres_deg", &s->hres_deg);
  if (s->hres_deg > 90.0) r.fail("sensor.hres_deg", "must be <= 90");
  r.positive("max_range_m", &s->max_range_m);
  r.number("min_range_m", &s->min_range_m);
  if (s->min_range_m < 0 || s->min_range_m >= s->max_range_m) {
    r.fail("sensor.min_range_m", "must be in [0, max_range_m)");
  }
  r.positive("rate_hz", &s->rate_hz);
  r.number("mount_height_m", &s->mount_height_m);
  r.number("range_noise_std_m", &s->range_noise_std_m);
  if (s->range_noise_std_m < 0) r.fail("sensor.range_noise_std_m", "must be >= 0");
  r.unit("dropout_prob", &s->dropout_prob);
  r.number("intensity_noise", &s->intensity_noise);
  if (s->intensity_noise < 0) r.fail("sensor.intensity_noise", "must be >= 0");
  r.boolean("motion_distortion", &s->motion_distortion);
  r.string("time_field", &s->time_field);
  if (s->time_field != "time" && s->time_field != "t") {
    r.fail("sensor.time_field", "must be time (Velodyne, float32 s) or t (Ouster, uint32 ns)");
  }
  if (const json* seed = r.get("seed", false)) {
    if (!seed->is_number_unsigned()) r.fail("sensor.seed", "expected an integer >= 0");
    s->seed = seed->get<uint64_t>();
  }
}

}  // namespace

bool applySensorPreset(const std::string& model, SensorSpec* s) {
  // Datasheet values: VLP-16 1800 firings per turn at 10 Hz; Ouster 1024 columns per turn.
  if (model == "vlp16") {
    s->rings = 16, s->vfov_deg = 30.0, s->hres_deg = 0.2, s->max_range_m = 100.0;
    s->time_field = "time";
  } else if (model == "os1_64") {
    s->rings = 64, s->vfov_deg = 45.0, s->hres_deg = 360.0 / 1024, s->max_range_m = 120.0;
    s->time_field = "t";
  } else if (model == "os0_128") {
    s->rings = 128, s->vfov_deg = 90.0, s->hres_deg = 360.0 / 1024, s->max_range_m = 50.0;
    s->time_field = "t";
  } else {
    return false;
  }
  s->model = model;
  return true;
}

World parseWorld(const nlohmann::json& j, const std::string& name) {
  World w;
  ObjectReader top(j, "", name);
  top.string("name", &w.name);
  forEach(top, "walls", [&](const json& e, const std::string& path) {
    ObjectReader r(e, path, name);
    Wall wall;
    wall.from = r.point2("from");
    wall.to = r.point2("to");
    if ((wall.to - wall.from).norm() < 1e-6) r.fail(path, "from and to are the same point");
    r.number("z_min", &wall.z_min);
    r.number("z_max", &wall.z_max);
    if (!(wall.z_max > wall.z_min)) r.fail(r.sub("z_max"), "must be > z_min");
    r.positive("thickness", &wall.thickness);
    r.unit("reflectivity", &wall.reflectivity);
    w.walls.push_back(wall);
  });
  forEach(top, "boxes", [&](const json& e, const std::string& path) {
    ObjectReader r(e, path, name);
    Box box;
    box.center = r.point(*r.get("center", true), r.sub("center"), 3);
    box.size = r.point(*r.get("size", true), r.sub("size"), 3);
    if ((box.size.array() <= 0).any()) r.fail(r.sub("size"), "every extent must be > 0");
    r.number("yaw_deg", &box.yaw_deg);
    r.unit("reflectivity", &box.reflectivity);
    w.boxes.push_back(box);
  });
  parseHorizontal(top, "floors", 0.3, &w.floors);
  parseHorizontal(top, "ceilings", 0.5, &w.ceilings);
  std::set<std::string> ids;
  forEach(top, "rooms", [&](const json& e, const std::string& path) {
    ObjectReader r(e, path, name);
    Room room;
    r.string("id", &room.id, true);
    if (room.id.empty()) r.fail(r.sub("id"), "must not be empty");
    if (!ids.insert(room.id).second) r.fail(r.sub("id"), "duplicate id '" + room.id + "'");
    r.string("kind", &room.kind);
    if (room.kind != "room" && room.kind != "corridor") {
      r.fail(r.sub("kind"), "expected \"room\" or \"corridor\"");
    }
    room.polygon = r.polygon("polygon");
    w.rooms.push_back(room);
  });
  parseTrajectory(top, &w.trajectory);
  parseSensor(top, &w.sensor);
  if (w.floors.empty()) top.fail("floors", "a world needs at least one floor polygon");
  return w;
}

nlohmann::json readJsonFile(const std::string& path) {
  std::ifstream in(path);
  if (!in) throw WorldError(path + ": cannot open file");
  nlohmann::json j;
  try {
    in >> j;
  } catch (const nlohmann::json::parse_error& e) {
    throw WorldError(path + ": invalid JSON: " + e.what());
  }
  return j;
}

World loadWorld(const std::string& path) { return parseWorld(readJsonFile(path), path); }

bool pointInPolygon(const Polygon2& poly, const Eigen::Vector2d& p) {
  bool inside = false;
  for (size_t i = 0, j = poly.size() - 1; i < poly.size(); j = i++) {
    const Eigen::Vector2d& a = poly[i];
    const Eigen::Vector2d& b = poly[j];
    if ((a.y() > p.y()) != (b.y() > p.y()) &&
        p.x() < (b.x() - a.x()) * (p.y() - a.y()) / (b.y() - a.y()) + a.x()) {
      inside = !inside;
    }
  }
  return inside;
}

double polygonArea(const Polygon2& poly) {
  double a = 0.0;
  for (size_t i = 0, j = poly.size() - 1; i < poly.size(); j = i++) {
    a += poly[j].x() * poly[i].y() - poly[i].x() * poly[j].y();
  }
  return 0.5 * a;
}

}  // namespace tacs::sim
