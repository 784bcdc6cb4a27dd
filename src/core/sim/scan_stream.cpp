#include "tacs_graphs/sim/scan_stream.h"

#include <algorithm>
#include <cmath>

#include "tacs_graphs/sim/sim_random.h"

namespace tacs::sim {
namespace {

constexpr double kPi = 3.14159265358979323846;

World withStart(const World& world, int start_waypoint) {
  World started = world;
  started.trajectory = startingAtWaypoint(world.trajectory, start_waypoint, world.name);
  return started;
}

}  // namespace

ScanStream::ScanStream(const World& world, const SimOptions& options)
    : world_(withStart(world, options.start_waypoint)),
      options_(options),
      sensor_(world.sensor),
      seed_(options.seed.value_or(world.sensor.seed)),
      path_(world_, seed_, world.name) {
  if (options.motion_distortion) sensor_.motion_distortion = *options.motion_distortion;
  caster_ = std::make_unique<RayCaster>(world_);
  double duration = path_.duration();
  if (options.duration_s > 0) duration = std::min(duration, options.duration_s);
  // Every sweep starts within the path; at least one.
  count_ = std::max<size_t>(1, static_cast<size_t>(std::floor(duration * sensor_.rate_hz)));

  // Beams evenly spread over the vertical field of view, ring 0 lowest.
  const double half = 0.5 * sensor_.vfov_deg * kPi / 180.0;
  for (int r = 0; r < sensor_.rings; ++r) {
    const double el = sensor_.rings == 1 ? 0.0 : -half + 2.0 * half * r / (sensor_.rings - 1);
    cos_el_.push_back(std::cos(el));
    sin_el_.push_back(std::sin(el));
  }
  // Firings: the head turns clockwise seen from above, starting behind the sensor (azimuth 180).
  const int columns = std::max(1, static_cast<int>(std::round(360.0 / sensor_.hres_deg)));
  for (int c = 0; c < columns; ++c) {
    const double az = kPi - 2.0 * kPi * c / columns;
    cos_az_.push_back(std::cos(az));
    sin_az_.push_back(std::sin(az));
  }
}

Pose3 ScanStream::baseToSensor() const {
  return poseFromXyzRpy(0.0, 0.0, sensor_.mount_height_m, 0.0, 0.0, 0.0);
}

Trajectory ScanStream::groundTruth() const {
  Trajectory out(count_);
  for (size_t k = 0; k < count_; ++k) {
    out[k].stamp = options_.start_stamp + k / sensor_.rate_hz;
    out[k].pose = path_.poseAt(k / sensor_.rate_hz);
  }
  return out;
}

bool ScanStream::next(SimScan* scan) {
  if (next_ >= count_) return false;
  render(next_++, scan);
  return true;
}

void ScanStream::render(size_t index, SimScan* scan) const {
  const double t0 = index / sensor_.rate_hz;
  scan->stamp = options_.start_stamp + t0;
  scan->T_world_base = path_.poseAt(t0);
  scan->points.clear();
  // Blocks of firings cast side by side, each with its own primitive marks, and joined in firing
  // order: every ray's noise is seeded by its own index, so the sweep is the same for any
  // number of threads.
  constexpr size_t kColumnsPerBlock = 64;
  const size_t columns = cos_az_.size();
  const size_t blocks = (columns + kColumnsPerBlock - 1) / kColumnsPerBlock;
  std::vector<std::vector<SimPoint>> parts(blocks);
#pragma omp parallel
  {
    RayCaster::Marks marks = caster_->newMarks();
#pragma omp for schedule(dynamic, 1)
    for (size_t b = 0; b < blocks; ++b) {
      renderColumns(index, b * kColumnsPerBlock, std::min(columns, (b + 1) * kColumnsPerBlock),
                    &marks, &parts[b]);
    }
  }
  size_t total = 0;
  for (const auto& part : parts) total += part.size();
  scan->points.reserve(total);
  for (const auto& part : parts) scan->points.insert(scan->points.end(), part.begin(), part.end());
}

void ScanStream::renderColumns(size_t index, size_t begin, size_t end, RayCaster::Marks* marks,
                               std::vector<SimPoint>* out) const {
  const double t0 = index / sensor_.rate_hz;
  const double period = 1.0 / sensor_.rate_hz;
  const size_t columns = cos_az_.size();
  const Pose3 T_base_sensor = baseToSensor();
  Pose3 T_world_sensor = path_.poseAt(t0) * T_base_sensor;
  const uint64_t scan_key = mixSeed(seed_, index);
  out->reserve((end - begin) * cos_el_.size());
  RayHit hit;
  for (size_t c = begin; c < end; ++c) {
    const double dt = period * c / columns;
    if (sensor_.motion_distortion) T_world_sensor = path_.poseAt(t0 + dt) * T_base_sensor;
    const Eigen::Matrix3d R = T_world_sensor.linear();
    const Eigen::Vector3d origin = T_world_sensor.translation();
    for (size_t r = 0; r < cos_el_.size(); ++r) {
      const Eigen::Vector3d dir_s(cos_el_[r] * cos_az_[c], cos_el_[r] * sin_az_[c], sin_el_[r]);
      const Eigen::Vector3d dir_w = R * dir_s;
      if (!caster_->cast(origin, dir_w, sensor_.max_range_m, &hit, marks)) continue;
      const RayNoise noise(mixSeed(scan_key, c * cos_el_.size() + r));
      if (noise.uniform < sensor_.dropout_prob) continue;
      const double range = hit.range + sensor_.range_noise_std_m * noise.gauss_a;
      if (range < sensor_.min_range_m || range > sensor_.max_range_m) continue;
      // Lambertian-like return: reflectivity times incidence cosine, fading slowly with range.
      const double incidence = std::abs(hit.normal.dot(dir_w));
      const double intensity =
          255.0 * hit.reflectivity * (0.25 + 0.75 * incidence) / (1.0 + 0.02 * hit.range) +
          sensor_.intensity_noise * noise.gauss_b;
      const Eigen::Vector3d p = dir_s * range;
      out->push_back({static_cast<float>(p.x()), static_cast<float>(p.y()),
                      static_cast<float>(p.z()),
                      static_cast<float>(std::clamp(intensity, 0.0, 255.0)),
                      static_cast<uint16_t>(r), static_cast<float>(dt)});
    }
  }
}

PointCloud toPointCloud(const SimScan& scan) {
  PointCloud cloud;
  cloud.header.stamp = static_cast<uint64_t>(std::llround(scan.stamp * 1e6));
  cloud.header.frame_id = "velodyne";
  cloud.reserve(scan.points.size());
  for (const auto& p : scan.points) {
    pcl::PointXYZI q;
    q.x = p.x, q.y = p.y, q.z = p.z, q.intensity = p.intensity;
    cloud.push_back(q);
  }
  cloud.width = cloud.size();
  cloud.height = 1;
  cloud.is_dense = true;
  return cloud;
}

std::vector<double> rawPointTimes(const SimScan& scan, const std::string& field) {
  std::vector<double> raw;
  raw.reserve(scan.points.size());
  for (const auto& p : scan.points) {
    raw.push_back(field == "t" ? static_cast<double>(std::llround(double{p.time} * 1e9))
                               : static_cast<double>(p.time));
  }
  return raw;
}

}  // namespace tacs::sim
