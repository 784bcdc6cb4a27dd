// The bridge from the ROS parameter server to the core's Config structs.
//
// Launch files load a YAML file from config/ into a namespace (default /tacs); every node reads
// the whole PipelineConfig from there, so nodes and offline tools share one file and one struct.
#pragma once

#include <ros/node_handle.h>
#include <xmlrpcpp/XmlRpcValue.h>

#include <nlohmann/json.hpp>
#include <string>

#include "tacs_graphs/pipeline/pipeline_config.h"

namespace tacs {

/// Converts an XmlRpc value (as returned by NodeHandle::getParam) to JSON.
nlohmann::json xmlRpcToJson(XmlRpc::XmlRpcValue& value);

/// Reads the PipelineConfig from the parameter namespace `ns` (absent keys keep defaults),
/// validates it, warns once per unknown key and logs the effective values at debug level.
/// Throws ConfigError naming the parameter; nodes catch it, log it and shut down.
PipelineConfig loadPipelineConfigFromRos(const ros::NodeHandle& nh, const std::string& ns);

/// A node-private number with its lower bound, checked like the YAML: throws ConfigError
/// ("<name>: must be > 0, got -1") unless value > min (or >= min when `inclusive`).
double checkedParam(const std::string& name, double value, double min, bool inclusive);

/// Reads the private parameter `~name` (default `fallback`) and checks it (checkedParam()); the
/// error names the resolved parameter.
double boundedParam(const ros::NodeHandle& pnh, const std::string& name, double fallback,
                    double min, bool inclusive);

}  // namespace tacs
