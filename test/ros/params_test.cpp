// The parameter-server bridge, tested on XmlRpc values built in memory (no ROS master).
#include <gtest/gtest.h>

#include "tacs_graphs/ros/params.h"

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

}  // namespace
}  // namespace tacs
