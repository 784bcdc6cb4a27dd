// bench_walls_worlds: wall extraction and wall landmarks on the simulated worlds with
// ground-truth poses, scored against the wall faces of the world files.
//
//   bench_walls_worlds [--worlds DIR] [--world NAME|FILE]... [--config YAML] [--verbose]
//
// Per world a keyframe is taken every 0.5 m of ground-truth path; its scan goes to the levelled
// base frame, is voxelised at 0.1 m and given to WallExtractor; the walls and the surfaces seen
// over are moved to the world frame and fed to WallMap (addSeenOver, associate, mergeDuplicates
// at every keyframe, as the backend does). A detection is a wall detection unless the landmark it
// joins is no wall (WallMap::walls(): it lies on a surface seen over before, or is too short).
// Ground truth: each wall box of the world has two long faces, cut where another full-height wall
// stands against them (a face running behind a partition is a wall in each room); the faces of
// full-height walls (z_max >= 1.5 m) longer than 1.5 m count, pieces shorter than 0.6 m do not. At
// a keyframe a face is visible when it lies within 10 m of the robot and at least 50 points of the
// raw scan lie within 5 cm of it, spread over at least 0.6 m along it (the extractor's shortest
// wall; occluded faces and faces of which only a door jamb is seen do not count). A detection is a
// true positive when it matches a visible face: normals within 10 deg (same side), plane distance
// at the detection's midpoint within 0.15 m, overlapping extents. P and R are micro-averaged over
// the keyframes; "P <= 10 m" counts only detections within the visible range, where the ground
// truth is defined; "P any" also accepts a match with any vertical surface of the world (half
// walls, rails, pit walls, box sides, faces out of range or barely seen). After the run, the walls
// of the map (WallMap::walls()) are counted against the faces ever visible ("on those faces":
// walls that match one of them; the others sit on furniture, pillars, half walls, ...); "held
// twice" counts faces matched by two or more walls, "stray" walls that match no surface of the
// world. Target: walls within 10 % of the faces ever visible, none held twice.
#include <Eigen/Geometry>
#include <algorithm>
#include <cmath>
#include <cstdio>
#include <filesystem>
#include <string>
#include <vector>

#include "bench_common.h"
#include "bench_worlds_common.h"
#include "tacs_graphs/odometry/preprocess.h"
#include "tacs_graphs/sim/scan_stream.h"
#include "tacs_graphs/walls/wall_extractor.h"
#include "tacs_graphs/walls/wall_map.h"

namespace {

using tacs::Pose3;

constexpr double kKeyframeDistance = 0.5;    // [m] of ground-truth path between keyframes
constexpr double kVoxel = 0.1;               // [m] voxel of the keyframe cloud
constexpr double kMinFaceLength = 1.5;       // [m] shorter faces are not ground-truth walls
constexpr double kMinWallTop = 1.5;          // [m] full-height walls reach this high
constexpr double kVisibleRange = 10.0;       // [m] faces farther from the robot do not count
constexpr double kFaceBand = 0.05;           // [m] scan points this close to a face see it
constexpr size_t kMinFacePoints = 50;        // scan points that make a face visible...
constexpr double kMinFaceSpan = 0.6;         // [m] ...spread this far along it
constexpr double kMaxNormalAngleDeg = 10.0;  // match gates
constexpr double kMaxPlaneDistance = 0.15;   // [m]

// One long face of a wall box or one side of a box: the line n.p + d = 0 (n horizontal, pointing
// away from the box), bounded by a and b, between heights z_min and z_max.
struct Face {
  Eigen::Vector2d n, a, b;
  double d, z_min, z_max;
  bool ground_truth;  // full height and long enough
  double length() const { return (b - a).norm(); }
};

// Interval [t0, t1] of the line a + t dir inside the footprint of wall `w`; empty (t0 >= t1)
// when the line misses it.
std::pair<double, double> coveredBy(const Eigen::Vector2d& a, const Eigen::Vector2d& dir,
                                    const tacs::sim::Wall& w) {
  const Eigen::Vector2d u = (w.to - w.from).normalized(), v(-u.y(), u.x());
  double t0 = -1e9, t1 = 1e9;
  // p(t) = a + t dir must satisfy 0 <= u.(p - from) <= |to - from| and |v.(p - from)| <= th / 2:
  // each bound is linear in t.
  auto bound = [&](const Eigen::Vector2d& axis, double lo, double hi) {
    const double c = axis.dot(a - w.from), k = axis.dot(dir);
    if (std::abs(k) < 1e-9) {
      if (c < lo || c > hi) t0 = t1 = 0.0;
      return;
    }
    const double ta = (lo - c) / k, tb = (hi - c) / k;
    t0 = std::max(t0, std::min(ta, tb));
    t1 = std::min(t1, std::max(ta, tb));
  };
  bound(u, 0.0, (w.to - w.from).norm());
  bound(v, -0.5 * w.thickness, 0.5 * w.thickness);
  return {t0, t1};
}

// The long faces of the wall boxes, cut where another full-height wall stands against them: a
// face running behind a partition is two walls to anyone in front of it (two rooms).
void appendWallFaces(const tacs::sim::World& world, std::vector<Face>* faces) {
  for (size_t i = 0; i < world.walls.size(); ++i) {
    const auto& w = world.walls[i];
    const Eigen::Vector2d u = (w.to - w.from).normalized();
    for (double side : {1.0, -1.0}) {
      const Eigen::Vector2d n = side * Eigen::Vector2d(-u.y(), u.x());
      const Eigen::Vector2d a = w.from + 0.5 * w.thickness * n;
      const double length = (w.to - w.from).norm();
      std::vector<std::pair<double, double>> cuts;
      for (size_t j = 0; j < world.walls.size(); ++j) {
        if (j == i || world.walls[j].z_max < kMinWallTop) continue;
        // Probed 2 cm in front of the face: a wall standing against it reaches there.
        const auto [t0, t1] = coveredBy(a + 0.02 * n, u, world.walls[j]);
        if (t1 > t0 && t1 > 0.0 && t0 < length) cuts.emplace_back(t0, t1);
      }
      std::sort(cuts.begin(), cuts.end());
      double start = 0.0;
      cuts.emplace_back(length, length);
      for (const auto& [t0, t1] : cuts) {
        if (t0 > start) {
          Face f;
          f.n = n;
          f.a = a + start * u;
          f.b = a + std::min(t0, length) * u;
          f.d = -f.n.dot(f.a);
          f.z_min = w.z_min;
          f.z_max = w.z_max;
          // The wall counts by its length; a piece of it too short to be seen does not.
          f.ground_truth =
              w.z_max >= kMinWallTop && length > kMinFaceLength && f.length() >= kMinFaceSpan;
          faces->push_back(f);
        }
        start = std::max(start, t1);
      }
    }
  }
}

std::vector<Face> facesOf(const tacs::sim::World& world) {
  std::vector<Face> faces;
  appendWallFaces(world, &faces);
  // The four sides of every box (furniture, cabinets, pillars): surfaces, never ground truth.
  for (const auto& box : world.boxes) {
    const double yaw = box.yaw_deg * M_PI / 180.0;
    const Eigen::Vector2d ux(std::cos(yaw), std::sin(yaw)), uy(-ux.y(), ux.x());
    const Eigen::Vector2d c = box.center.head<2>();
    for (int axis = 0; axis < 2; ++axis) {
      const Eigen::Vector2d n0 = axis == 0 ? ux : uy, along = axis == 0 ? uy : ux;
      const double half_n = 0.5 * box.size[axis], half_along = 0.5 * box.size[1 - axis];
      for (double side : {1.0, -1.0}) {
        Face f;
        f.n = side * n0;
        f.a = c + half_n * f.n - half_along * along;
        f.b = c + half_n * f.n + half_along * along;
        f.d = -f.n.dot(f.a);
        f.z_min = box.center.z() - 0.5 * box.size.z();
        f.z_max = box.center.z() + 0.5 * box.size.z();
        f.ground_truth = false;
        faces.push_back(f);
      }
    }
  }
  return faces;
}

// Position of p along the face, 0 at a, length() at b.
double alongFace(const Face& f, const Eigen::Vector2d& p) {
  return (f.b - f.a).normalized().dot(p - f.a);
}

double distanceToSegment(const Eigen::Vector2d& a, const Eigen::Vector2d& b,
                         const Eigen::Vector2d& p) {
  const Eigen::Vector2d ab = b - a;
  const double t = std::clamp(ab.dot(p - a) / std::max(ab.squaredNorm(), 1e-12), 0.0, 1.0);
  return (a + t * ab - p).norm();
}

// A wall (detection or landmark, world frame) matches a face: same side, same plane, overlap.
bool matches(const Eigen::Vector3d& normal, const Eigen::Vector2d endpoints[2], const Face& f) {
  const Eigen::Vector2d n = normal.head<2>().normalized();
  if (n.dot(f.n) < std::cos(kMaxNormalAngleDeg * M_PI / 180.0)) return false;
  const Eigen::Vector2d mid = 0.5 * (endpoints[0] + endpoints[1]);
  if (std::abs(f.n.dot(mid) + f.d) > kMaxPlaneDistance) return false;
  const double t0 = alongFace(f, endpoints[0]), t1 = alongFace(f, endpoints[1]);
  return std::min(std::max(t0, t1), f.length()) > std::max(std::min(t0, t1), 0.0);
}

// Ground-truth faces visible from a scan (raw points in the world frame) at robot position xy.
std::vector<bool> visibleFaces(const std::vector<Face>& faces,
                               const std::vector<Eigen::Vector3d>& points,
                               const Eigen::Vector2d& robot) {
  std::vector<bool> visible(faces.size(), false);
  for (size_t k = 0; k < faces.size(); ++k) {
    const Face& f = faces[k];
    if (!f.ground_truth || distanceToSegment(f.a, f.b, robot) > kVisibleRange) continue;
    size_t seen = 0;
    double t_min = f.length(), t_max = 0.0;
    for (const auto& p : points) {
      if (std::abs(f.n.dot(p.head<2>()) + f.d) > kFaceBand) continue;
      if (p.z() < f.z_min + kFaceBand || p.z() > f.z_max - kFaceBand) continue;
      // The end caps (door jambs) touch the face's plane: their points are not on the face.
      const double t = alongFace(f, p.head<2>());
      if (t < kFaceBand || t > f.length() - kFaceBand) continue;
      ++seen;
      t_min = std::min(t_min, t);
      t_max = std::max(t_max, t);
    }
    visible[k] = seen >= kMinFacePoints && t_max - t_min >= kMinFaceSpan;
  }
  return visible;
}

// Why a detection is no true positive, in this order: it lies on a ground-truth face beyond the
// visible range, on one in range but barely seen, on a full-height surface shorter than a
// ground-truth wall (pillar, cabinet), on a low surface (half wall, furniture), on nothing.
enum Miss { kFar, kBarelySeen, kShort, kLow, kNothing, kMissKinds };
const char* const kMissNames[kMissKinds] = {"far", "barely seen", "short", "low", "nothing"};

Miss missKind(const Face& f, const std::vector<bool>& visible, size_t k, bool in_range) {
  if (f.ground_truth) return in_range && !visible[k] ? kBarelySeen : kFar;
  return f.z_max >= kMinWallTop ? kShort : kLow;
}

struct WorldScore {
  size_t keyframes = 0;
  size_t detections = 0, true_positives = 0, any_face = 0;  // per-keyframe detections
  size_t near_detections = 0, near_true_positives = 0;      // ... within the visible range
  size_t misses[kMissKinds] = {};                           // detections that are no TP, by kind
  size_t visible = 0, found = 0;                            // per-keyframe visible faces
  size_t ever_visible = 0, landmarks = 0, on_faces = 0, held = 0, held_twice = 0, stray = 0;
  std::vector<double> ms;
};

WorldScore runWorld(const std::string& path, const tacs::bench::WorldsArgs& args) {
  const tacs::sim::World world = tacs::sim::loadWorld(path);
  const std::vector<Face> faces = facesOf(world);
  tacs::sim::ScanStream stream(world, tacs::sim::SimOptions{});
  const tacs::Trajectory gt = stream.groundTruth();
  const Pose3 T_base_sensor = stream.baseToSensor();
  const tacs::WallExtractor extractor{args.config.walls.extraction};
  tacs::WallMap walls(args.config.walls.association);

  WorldScore score;
  std::vector<bool> ever_visible(faces.size(), false);
  Eigen::Vector3d last(1e9, 1e9, 1e9);
  tacs::sim::SimScan scan;
  for (size_t i = 0; i < gt.size(); ++i) {
    if ((gt[i].pose.translation() - last).norm() < kKeyframeDistance) continue;
    last = gt[i].pose.translation();
    ++score.keyframes;
    stream.render(i, &scan);
    const Pose3 T_world_sensor = scan.T_world_base * T_base_sensor;
    const Pose3 T_world_level = tacs::bench::levelledPose(scan.T_world_base);
    std::vector<Eigen::Vector3d> points;
    points.reserve(scan.points.size());
    for (const auto& p : scan.points)
      points.push_back(T_world_sensor * Eigen::Vector3d(p.x, p.y, p.z));
    const std::vector<bool> visible = visibleFaces(faces, points, last.head<2>());

    const tacs::PointCloud cloud = tacs::voxelDownsample(
        tacs::bench::levelledCloud(scan, T_base_sensor, T_world_level), kVoxel);
    const Eigen::Vector3d sensor = T_world_level.inverse() * T_world_sensor.translation();
    const tacs::WallExtractionResult extracted = extractor.extract(cloud, sensor);
    score.ms.push_back(extracted.time_ms);
    // What the map makes of the detections: a surface seen over before is no wall.
    walls.addSeenOver(extracted.seen_over, T_world_level);
    const auto associations = walls.associate(extracted.walls, T_world_level);
    std::vector<bool> found(faces.size(), false);
    for (const auto& a : associations) {
      if (!walls.isWall(a.landmark_id)) continue;
      const tacs::WallSegment w =
          tacs::transformWall(extracted.walls[a.observation_index], T_world_level);
      const bool near =
          distanceToSegment(w.endpoints[0], w.endpoints[1], last.head<2>()) <= kVisibleRange;
      bool tp = false, any = false;
      Miss miss = kNothing;
      for (size_t k = 0; k < faces.size(); ++k) {
        if (!matches(w.normal, w.endpoints, faces[k])) continue;
        any = true;
        if (visible[k]) tp = found[k] = true;
        miss = std::min(miss, missKind(faces[k], visible, k, near));
      }
      score.detections++;
      score.true_positives += tp;
      score.any_face += any;
      score.near_detections += near;
      score.near_true_positives += near && tp;
      if (!tp) ++score.misses[miss];
    }
    for (size_t k = 0; k < faces.size(); ++k) {
      score.visible += visible[k];
      score.found += visible[k] && found[k];
      ever_visible[k] = ever_visible[k] || visible[k];
    }
    walls.mergeDuplicates();
  }

  std::vector<int> holders(faces.size(), 0);
  for (const auto& [id, lm] : walls.walls()) {
    ++score.landmarks;
    bool any = false;
    int on_faces = 0;
    for (size_t k = 0; k < faces.size(); ++k) {
      if (!matches(lm.normal, lm.endpoints, faces[k])) continue;
      any = true;
      holders[k] += ever_visible[k];
      on_faces += ever_visible[k];
    }
    if (on_faces >= 2 && args.verbose) {
      std::printf("|   landmark %u spans %d faces: (%.2f, %.2f)-(%.2f, %.2f) |\n", id, on_faces,
                  lm.endpoints[0].x(), lm.endpoints[0].y(), lm.endpoints[1].x(),
                  lm.endpoints[1].y());
    }
    score.stray += !any;
    if (args.verbose && any && on_faces == 0) {
      Miss kind = kNothing;
      for (size_t k = 0; k < faces.size(); ++k) {
        if (matches(lm.normal, lm.endpoints, faces[k])) {
          kind = std::min(kind, missKind(faces[k], ever_visible, k, true));
        }
      }
      std::printf(
          "|   landmark %u on no wall: %s surface, (%.2f, %.2f)-(%.2f, %.2f), z %.2f-%.2f, seen %u "
          "times |\n",
          id, kMissNames[kind], lm.endpoints[0].x(), lm.endpoints[0].y(), lm.endpoints[1].x(),
          lm.endpoints[1].y(), lm.z_min, lm.z_max, lm.observations);
    }
    score.on_faces += on_faces > 0;
    if (!any && args.verbose) {
      std::printf(
          "|   stray landmark %u: n (%.2f, %.2f), %.2f m long, (%.2f, %.2f)-(%.2f, %.2f) |\n", id,
          lm.normal.x(), lm.normal.y(), lm.length(), lm.endpoints[0].x(), lm.endpoints[0].y(),
          lm.endpoints[1].x(), lm.endpoints[1].y());
    }
  }
  for (size_t k = 0; k < faces.size(); ++k) {
    score.ever_visible += ever_visible[k];
    score.held += holders[k] >= 1;
    score.held_twice += holders[k] >= 2;
    if (args.verbose && ever_visible[k] && holders[k] != 1) {
      std::printf("|   face (%.2f, %.2f)-(%.2f, %.2f) n (%.0f, %.0f): %d landmarks |\n",
                  faces[k].a.x(), faces[k].a.y(), faces[k].b.x(), faces[k].b.y(), faces[k].n.x(),
                  faces[k].n.y(), holders[k]);
    }
  }
  return score;
}

}  // namespace

int main(int argc, char** argv) {
  tacs::setUpProcess(argv);
  tacs::bench::WorldsArgs args;
  const char* usage =
      "Usage: bench_walls_worlds [--worlds DIR] [--world NAME|FILE]... [--config YAML] "
      "[--verbose]\nWall extraction precision / recall per keyframe and wall landmarks against "
      "the wall faces of the simulated worlds (ground-truth poses).\n";
  if (!tacs::bench::parseWorldsArgs(argc, argv, usage, &args)) return 2;
  std::printf(
      "Walls on the simulated worlds, keyframe every %.1f m, ground-truth poses; load %s\n\n"
      "| world | kf | detections | P | P <= %.0f m | P any | visible faces | R "
      "| faces ever visible | walls | on those faces | faces held | held twice "
      "| stray walls | extract ms |\n"
      "|---|---|---|---|---|---|---|---|---|---|---|---|---|---|---|\n",
      kKeyframeDistance, tacs::bench::loadAverage().c_str(), kVisibleRange);
  std::vector<std::pair<std::string, WorldScore>> scores;
  for (const auto& path : tacs::bench::worldPaths(&args)) {
    try {
      const WorldScore s = runWorld(path, args);
      scores.emplace_back(std::filesystem::path(path).stem().string(), s);
      std::printf(
          "| %-17s | %4zu | %5zu | %5.3f | %5.3f | %5.3f | %5zu | %5.3f | %3zu | %3zu | %3zu | "
          "%3zu | %2zu | %2zu | %5.1f |\n",
          scores.back().first.c_str(), s.keyframes, s.detections,
          tacs::bench::ratio(s.true_positives, s.detections),
          tacs::bench::ratio(s.near_true_positives, s.near_detections),
          tacs::bench::ratio(s.any_face, s.detections), s.visible,
          tacs::bench::ratio(s.found, s.visible), s.ever_visible, s.landmarks, s.on_faces, s.held,
          s.held_twice, s.stray, tacs::bench::meanOf(s.ms));
      std::fflush(stdout);
    } catch (const std::exception& e) {
      std::fprintf(stderr, "%s: %s\n", path.c_str(), e.what());
      return 1;
    }
  }
  std::printf(
      "\nDetections that are no true positive, by what they lie on (share of all):\n\n| world |");
  for (const char* name : kMissNames) std::printf(" %s |", name);
  std::printf("\n|---|---|---|---|---|---|\n");
  for (const auto& [name, s] : scores) {
    std::printf("| %-17s |", name.c_str());
    for (size_t m : s.misses) std::printf(" %5.3f |", tacs::bench::ratio(m, s.detections));
    std::printf("\n");
  }
  return 0;
}
