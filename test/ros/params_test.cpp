// The parameter-server bridge, tested on XmlRpc values built in memory (no ROS master).
#include "tacs_graphs/ros/params.h"

#include <gtest/gtest.h>

#include <cmath>

namespace tacs {
namespace {

TEST(XmlRpcToJson, ConvertsNestedStructsArraysAndScalars) {
  XmlRpc::XmlRpcValue root;
  root["frames"]["base_frame"] = std::string("body");
  root["frames"]["base_to_sensor"][0] = 0.1;
  root["frames"]["base_to_sensor"][1] = 2;
  root["flag"] = true;
  const nlohmann::json j = xmlRpcToJson(root);
  EXPECT_EQ(j["frames"]["base_frame"], "body");
  EXPECT_DOUBLE_EQ(j["frames"]["base_to_sensor"][0].get<double>(), 0.1);
  EXPECT_TRUE(j["frames"]["base_to_sensor"][1].is_number_integer());
  EXPECT_EQ(j["flag"], true);
}

TEST(XmlRpcToJson, FeedsThePipelineConfig) {
  XmlRpc::XmlRpcValue root;
  root["frames"]["base_frame"] = std::string("body");
  PipelineConfig config;
  std::vector<std::string> unknown;
  configFromJson(xmlRpcToJson(root), "ROS parameter /tacs", &config, &unknown);
  EXPECT_EQ(config.frames.base_frame, "body");
  root["frames"]["base_to_sensor"] = std::string("oops");
  EXPECT_THROW(configFromJson(xmlRpcToJson(root), "ROS parameter /tacs", &config, &unknown),
               ConfigError);
}

TEST(NodeParams, ABadPrivateNumberIsAConfigErrorNamingIt) {
  EXPECT_DOUBLE_EQ(checkedParam("/backend/tf_rate_hz", 20.0, 0.0, false), 20.0);
  EXPECT_DOUBLE_EQ(checkedParam("/room_segmentation/repose_angle_deg", 0.0, 0.0, true), 0.0);
  for (const double bad : {0.0, -1.0, std::nan("")}) {
    try {
      checkedParam("/backend/tf_rate_hz", bad, 0.0, false);
      ADD_FAILURE() << "accepted " << bad;
    } catch (const ConfigError& e) {
      EXPECT_NE(std::string(e.what()).find("/backend/tf_rate_hz: must be > 0, got"),
                std::string::npos)
          << e.what();
    }
  }
  EXPECT_THROW(checkedParam("/gicp_odometry/points_queue_size", 0, 1, true), ConfigError);
}

}  // namespace
}  // namespace tacs
