#include "tacs_graphs/ros/sim_bag_writer.h"

#include <nav_msgs/Odometry.h>
#include <sensor_msgs/point_cloud2_iterator.h>
#include <tf2_msgs/TFMessage.h>

#include <cmath>
#include <cstring>

namespace tacs {
namespace {

void fillPose(const Pose3& T, geometry_msgs::Point* p, geometry_msgs::Quaternion* q) {
  const Eigen::Quaterniond r(T.rotation());
  p->x = T.translation().x(), p->y = T.translation().y(), p->z = T.translation().z();
  q->x = r.x(), q->y = r.y(), q->z = r.z(), q->w = r.w();
}

}  // namespace

sensor_msgs::PointCloud2 simScanToPointCloud2(const sim::SimScan& scan, const std::string& frame_id,
                                              const std::string& time_field) {
  const bool ouster = time_field == "t";
  const bool timed = !time_field.empty();
  sensor_msgs::PointCloud2 msg;
  msg.header.stamp.fromSec(scan.stamp);
  msg.header.frame_id = frame_id;
  msg.height = 1;
  msg.width = scan.points.size();
  sensor_msgs::PointCloud2Modifier modifier(msg);
  // The count leaves the time field out when `timed` is false (the list is read up to it).
  modifier.setPointCloud2Fields(
      timed ? 6 : 5, "x", 1, sensor_msgs::PointField::FLOAT32, "y", 1,
      sensor_msgs::PointField::FLOAT32, "z", 1, sensor_msgs::PointField::FLOAT32, "intensity", 1,
      sensor_msgs::PointField::FLOAT32, "ring", 1, sensor_msgs::PointField::UINT16,
      ouster ? "t" : "time", 1,
      ouster ? sensor_msgs::PointField::UINT32 : sensor_msgs::PointField::FLOAT32);
  modifier.resize(scan.points.size());
  msg.is_dense = true;
  msg.is_bigendian = false;
  uint8_t* out = msg.data.data();
  for (const auto& p : scan.points) {
    std::memcpy(out + 0, &p.x, 4);
    std::memcpy(out + 4, &p.y, 4);
    std::memcpy(out + 8, &p.z, 4);
    std::memcpy(out + 12, &p.intensity, 4);
    std::memcpy(out + 16, &p.ring, 2);
    if (timed && ouster) {
      const uint32_t ns = static_cast<uint32_t>(std::llround(double{p.time} * 1e9));
      std::memcpy(out + 18, &ns, 4);
    } else if (timed) {
      std::memcpy(out + 18, &p.time, 4);
    }
    out += msg.point_step;
  }
  return msg;
}

SimBagWriter::SimBagWriter(const std::string& path, const Pose3& T_base_sensor,
                           const Options& options)
    : T_base_sensor_(T_base_sensor), options_(options) {
  bag_.open(path, rosbag::bagmode::Write);
}

SimBagWriter::~SimBagWriter() { close(); }

void SimBagWriter::close() {
  if (bag_.isOpen()) bag_.close();
}

void SimBagWriter::write(const sim::SimScan& scan) {
  ros::Time stamp;
  stamp.fromSec(scan.stamp);
  if (first_) {
    tf2_msgs::TFMessage tf;
    geometry_msgs::TransformStamped t;
    t.header.stamp = stamp;
    t.header.frame_id = options_.base_frame;
    t.child_frame_id = options_.sensor_frame;
    geometry_msgs::Point p;
    fillPose(T_base_sensor_, &p, &t.transform.rotation);
    t.transform.translation.x = p.x, t.transform.translation.y = p.y;
    t.transform.translation.z = p.z;
    tf.transforms.push_back(t);
    auto header = boost::make_shared<ros::M_string>();
    // A custom connection header replaces rosbag's own: it must carry the type fields too.
    (*header)["type"] = ros::message_traits::datatype<tf2_msgs::TFMessage>();
    (*header)["md5sum"] = ros::message_traits::md5sum<tf2_msgs::TFMessage>();
    (*header)["message_definition"] = ros::message_traits::definition<tf2_msgs::TFMessage>();
    (*header)["latching"] = "1";
    (*header)["callerid"] = "/tacs_sim";
    bag_.write("/tf_static", stamp, tf, header);
  }
  bag_.write(options_.cloud_topic, stamp,
             simScanToPointCloud2(scan, options_.sensor_frame,
                                  options_.point_times ? options_.time_field : std::string()));

  nav_msgs::Odometry odom;
  odom.header.stamp = stamp;
  odom.header.frame_id = options_.world_frame;
  odom.child_frame_id = options_.base_frame;
  fillPose(scan.T_world_base, &odom.pose.pose.position, &odom.pose.pose.orientation);
  if (!first_ && scan.stamp > previous_.stamp) {
    // Body-frame twist by backward difference over one sweep.
    const double dt = scan.stamp - previous_.stamp;
    const Pose3 delta = previous_.T_world_base.inverse() * scan.T_world_base;
    const Eigen::AngleAxisd aa(delta.rotation());
    const Eigen::Vector3d v = delta.translation() / dt, w = aa.axis() * aa.angle() / dt;
    odom.twist.twist.linear.x = v.x(), odom.twist.twist.linear.y = v.y();
    odom.twist.twist.linear.z = v.z();
    odom.twist.twist.angular.x = w.x(), odom.twist.twist.angular.y = w.y();
    odom.twist.twist.angular.z = w.z();
  }
  bag_.write(options_.odom_topic, stamp, odom);
  previous_.stamp = scan.stamp;
  previous_.T_world_base = scan.T_world_base;
  first_ = false;
}

}  // namespace tacs
