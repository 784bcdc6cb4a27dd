#include "tacs_graphs/ros/cloud_conversion.h"

#include <sensor_msgs/point_cloud2_iterator.h>

#include <cmath>
#include <cstring>

namespace tacs {
namespace {

const sensor_msgs::PointField* findField(const sensor_msgs::PointCloud2& msg, const char* name) {
  for (const auto& f : msg.fields) {
    if (f.name == name) return &f;
  }
  return nullptr;
}

size_t datatypeSize(uint8_t datatype) {
  switch (datatype) {
    case sensor_msgs::PointField::INT8:
    case sensor_msgs::PointField::UINT8:
      return 1;
    case sensor_msgs::PointField::INT16:
    case sensor_msgs::PointField::UINT16:
      return 2;
    case sensor_msgs::PointField::INT32:
    case sensor_msgs::PointField::UINT32:
    case sensor_msgs::PointField::FLOAT32:
      return 4;
    case sensor_msgs::PointField::FLOAT64:
      return 8;
    default:
      return 0;
  }
}

// Reads one field value as double; the message's byte order must match the host's (checked).
double readValue(const uint8_t* p, uint8_t datatype) {
  switch (datatype) {
    case sensor_msgs::PointField::INT8:
      return *reinterpret_cast<const int8_t*>(p);
    case sensor_msgs::PointField::UINT8:
      return *p;
    case sensor_msgs::PointField::INT16: {
      int16_t v;
      std::memcpy(&v, p, 2);
      return v;
    }
    case sensor_msgs::PointField::UINT16: {
      uint16_t v;
      std::memcpy(&v, p, 2);
      return v;
    }
    case sensor_msgs::PointField::INT32: {
      int32_t v;
      std::memcpy(&v, p, 4);
      return v;
    }
    case sensor_msgs::PointField::UINT32: {
      uint32_t v;
      std::memcpy(&v, p, 4);
      return v;
    }
    case sensor_msgs::PointField::FLOAT32: {
      float v;
      std::memcpy(&v, p, 4);
      return v;
    }
    case sensor_msgs::PointField::FLOAT64: {
      double v;
      std::memcpy(&v, p, 8);
      return v;
    }
  }
  return std::nan("");
}

CloudConversionResult reject(CloudConversionResult r, const std::string& why) {
  r.ok = false;
  r.error = why;
  return r;
}

const sensor_msgs::PointField* findTimeField(const sensor_msgs::PointCloud2& msg,
                                             const std::string& request) {
  if (request == "none") return nullptr;
  if (request != "auto") return findField(msg, request.c_str());
  for (const std::string& name : autoTimeFieldNames()) {
    if (const auto* f = findField(msg, name.c_str())) return f;
  }
  return nullptr;
}

}  // namespace

CloudConversionResult fromRosCloud(const sensor_msgs::PointCloud2& msg, PointCloud* cloud,
                                   const TimeFieldRequest& times) {
  CloudConversionResult result;
  cloud->clear();
  if (times.raw) times.raw->clear();
  const sensor_msgs::PointField* ft = times.raw ? findTimeField(msg, times.field) : nullptr;
  result.points_in = static_cast<size_t>(msg.width) * msg.height;
  const sensor_msgs::PointField* fx = findField(msg, "x");
  const sensor_msgs::PointField* fy = findField(msg, "y");
  const sensor_msgs::PointField* fz = findField(msg, "z");
  const sensor_msgs::PointField* fi = findField(msg, "intensity");
  if (!fx || !fy || !fz) {
    std::string names;
    for (const auto& f : msg.fields) names += (names.empty() ? "" : " ") + f.name;
    return reject(result, "missing x/y/z field (fields: " + (names.empty() ? "none" : names) + ")");
  }
  if (msg.is_bigendian) return reject(result, "big-endian clouds are not supported");
  for (const auto* f : {fx, fy, fz}) {
    if (f->datatype != sensor_msgs::PointField::FLOAT32 &&
        f->datatype != sensor_msgs::PointField::FLOAT64) {
      return reject(result, "field " + f->name + " is not float32/float64");
    }
  }
  for (const auto* f : {fx, fy, fz, fi, ft}) {
    if (f && (datatypeSize(f->datatype) == 0 ||
              f->offset + datatypeSize(f->datatype) > msg.point_step)) {
      return reject(result, "field " + f->name + " does not fit in point_step " +
                                std::to_string(msg.point_step));
    }
  }
  if (msg.height > 0 && msg.row_step < static_cast<uint64_t>(msg.width) * msg.point_step) {
    return reject(result, "row_step smaller than width * point_step");
  }
  if (msg.data.size() < static_cast<size_t>(msg.row_step) * msg.height) {
    return reject(result, "data holds " + std::to_string(msg.data.size()) + " bytes, expected " +
                              std::to_string(static_cast<size_t>(msg.row_step) * msg.height));
  }
  cloud->reserve(result.points_in);
  if (ft) {
    result.time_field = ft->name;
    times.raw->reserve(result.points_in);
  }
  for (uint32_t row = 0; row < msg.height; ++row) {
    const uint8_t* row_ptr = msg.data.data() + static_cast<size_t>(row) * msg.row_step;
    for (uint32_t col = 0; col < msg.width; ++col) {
      const uint8_t* p = row_ptr + static_cast<size_t>(col) * msg.point_step;
      pcl::PointXYZI q;
      q.x = static_cast<float>(readValue(p + fx->offset, fx->datatype));
      q.y = static_cast<float>(readValue(p + fy->offset, fy->datatype));
      q.z = static_cast<float>(readValue(p + fz->offset, fz->datatype));
      q.intensity = fi ? static_cast<float>(readValue(p + fi->offset, fi->datatype)) : 0.0f;
      if (!std::isfinite(q.x) || !std::isfinite(q.y) || !std::isfinite(q.z)) {
        ++result.non_finite;
        continue;
      }
      cloud->push_back(q);
      if (ft) times.raw->push_back(readValue(p + ft->offset, ft->datatype));
    }
  }
  cloud->width = static_cast<uint32_t>(cloud->size());
  cloud->height = 1;
  cloud->is_dense = true;
  result.ok = true;
  return result;
}

TimedScan fromRosCloudWithTimes(const sensor_msgs::PointCloud2& msg, double stamp,
                                const PointTimeConfig& config) {
  TimedScan scan;
  if (config.time_field == "none") {
    scan.conversion = fromRosCloud(msg, &scan.cloud);
    scan.times.reason = "disabled";
    scan.times.message = "odometry.point_times.time_field is none";
    return scan;
  }
  std::vector<double> raw;
  scan.conversion = fromRosCloud(msg, &scan.cloud, {config.time_field, &raw});
  if (!scan.conversion.ok) return scan;
  if (scan.conversion.time_field.empty()) {
    scan.times.reason = "no_field";
    scan.times.message = config.time_field == "auto"
                             ? "the cloud has no per-point time field (none of time, t, "
                               "timestamp, offset_time, time_stamp)"
                             : "the cloud has no field '" + config.time_field + "'";
    return scan;
  }
  scan.times = resolvePointTimes(scan.conversion.time_field, raw, stamp, config);
  return scan;
}

sensor_msgs::PointCloud2 toRosCloud(const PointCloud& cloud, const std::string& frame_id,
                                    double stamp) {
  sensor_msgs::PointCloud2 msg;
  msg.header.frame_id = frame_id;
  msg.header.stamp.fromSec(stamp);
  sensor_msgs::PointCloud2Modifier modifier(msg);
  modifier.setPointCloud2Fields(
      4, "x", 1, sensor_msgs::PointField::FLOAT32, "y", 1, sensor_msgs::PointField::FLOAT32, "z", 1,
      sensor_msgs::PointField::FLOAT32, "intensity", 1, sensor_msgs::PointField::FLOAT32);
  modifier.resize(cloud.size());
  sensor_msgs::PointCloud2Iterator<float> x(msg, "x"), y(msg, "y"), z(msg, "z"),
      intensity(msg, "intensity");
  for (const auto& p : cloud) {
    *x = p.x;
    *y = p.y;
    *z = p.z;
    *intensity = p.intensity;
    ++x, ++y, ++z, ++intensity;
  }
  return msg;
}

}  // namespace tacs
