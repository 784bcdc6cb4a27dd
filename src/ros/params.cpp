#include "tacs_graphs/ros/params.h"

#include <ros/console.h>

#include <cmath>
#include <sstream>

namespace tacs {

nlohmann::json xmlRpcToJson(XmlRpc::XmlRpcValue& value) {
  switch (value.getType()) {
    case XmlRpc::XmlRpcValue::TypeBoolean:
      return static_cast<bool>(value);
    case XmlRpc::XmlRpcValue::TypeInt:
      return static_cast<int>(value);
    case XmlRpc::XmlRpcValue::TypeDouble:
      return static_cast<double>(value);
    case XmlRpc::XmlRpcValue::TypeString:
      return static_cast<std::string>(value);
    case XmlRpc::XmlRpcValue::TypeArray: {
      nlohmann::json out = nlohmann::json::array();
      for (int i = 0; i < value.size(); ++i) out.push_back(xmlRpcToJson(value[i]));
      return out;
    }
    case XmlRpc::XmlRpcValue::TypeStruct: {
      nlohmann::json out = nlohmann::json::object();
      for (auto& kv : value) out[kv.first] = xmlRpcToJson(kv.second);
      return out;
    }
    default:
      return nullptr;  // date/time and binary values have no meaning in our configs
  }
}

PipelineConfig loadPipelineConfigFromRos(const ros::NodeHandle& nh, const std::string& ns) {
  XmlRpc::XmlRpcValue tree;
  nlohmann::json json = nlohmann::json::object();
  if (nh.getParam(ns, tree)) {
    json = xmlRpcToJson(tree);
  } else {
    ROS_WARN_STREAM("No parameters under '" << nh.resolveName(ns)
                                            << "': using the built-in defaults");
  }
  PipelineConfig config;
  std::vector<std::string> unknown;
  configFromJson(json, "ROS parameter " + nh.resolveName(ns), &config, &unknown);
  for (const auto& key : unknown) {
    ROS_WARN_STREAM("Unknown parameter " << nh.resolveName(ns) << "/" << key
                                         << " is ignored (a typo?)");
  }
  ROS_DEBUG_STREAM("Effective configuration: " << configToJson(config).dump());
  return config;
}

double checkedParam(const std::string& name, double value, double min, bool inclusive) {
  std::ostringstream reason;
  reason << "must be " << (inclusive ? ">= " : "> ") << min << ", got " << value;
  requireConfig(std::isfinite(value) && (inclusive ? value >= min : value > min), name,
                reason.str());
  return value;
}

double boundedParam(const ros::NodeHandle& pnh, const std::string& name, double fallback,
                    double min, bool inclusive) {
  return checkedParam(pnh.resolveName(name), pnh.param(name, fallback), min, inclusive);
}

}  // namespace tacs
