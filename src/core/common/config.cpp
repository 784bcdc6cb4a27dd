#include "tacs_graphs/common/config.h"

#include <yaml-cpp/yaml.h>

#include <algorithm>
#include <cerrno>
#include <cmath>
#include <cstdlib>
#include <fstream>
#include <limits>
#include <sstream>

namespace tacs {

void requireConfig(bool ok, const std::string& field, const std::string& reason) {
  if (!ok) throw ConfigError(field + ": " + reason);
}

namespace config_detail {

std::string joinPath(const std::string& path, const std::string& key) {
  return path.empty() ? key : path + "." + key;
}

namespace {
[[noreturn]] void typeError(const nlohmann::json& j, const std::string& path, const char* want) {
  throw ConfigError(path + ": expected " + want + ", got " + j.dump());
}
}  // namespace

void readScalar(const nlohmann::json& j, const std::string& path, double* out) {
  if (!j.is_number()) typeError(j, path, "a number");
  *out = j.get<double>();
}

void readScalar(const nlohmann::json& j, const std::string& path, float* out) {
  if (!j.is_number()) typeError(j, path, "a number");
  *out = j.get<float>();
}

void readScalar(const nlohmann::json& j, const std::string& path, int* out) {
  if (!j.is_number_integer()) typeError(j, path, "an integer");
  const auto v = j.get<int64_t>();
  if (v < std::numeric_limits<int>::min() || v > std::numeric_limits<int>::max()) {
    typeError(j, path, "an integer in int range");
  }
  *out = static_cast<int>(v);
}

void readScalar(const nlohmann::json& j, const std::string& path, unsigned* out) {
  if (!j.is_number_integer() || j.get<int64_t>() < 0) typeError(j, path, "a non-negative integer");
  *out = j.get<unsigned>();
}

void readScalar(const nlohmann::json& j, const std::string& path, bool* out) {
  if (!j.is_boolean()) typeError(j, path, "true or false");
  *out = j.get<bool>();
}

void readScalar(const nlohmann::json& j, const std::string& path, std::string* out) {
  if (!j.is_string()) typeError(j, path, "a string");
  *out = j.get<std::string>();
}

}  // namespace config_detail

ConfigReader::ConfigReader(const nlohmann::json& node, std::string path,
                           std::vector<std::string>* unknown_keys)
    : node_(node), path_(std::move(path)), unknown_keys_(unknown_keys) {}

void ConfigReader::finish() const {
  if (!node_.is_object()) return;
  const auto claimed = [this](const std::string& key) {
    return std::find(claimed_.begin(), claimed_.end(), key) != claimed_.end();
  };
  for (auto it = node_.begin(); it != node_.end(); ++it) {
    if (claimed(it.key())) continue;
    // Keys carry their unit: a key the unit was added to is an error naming the new key.
    for (const char* unit : {"_m", "_m2", "_deg", "_rad", "_s"}) {
      if (claimed(it.key() + unit)) {
        throw ConfigError(config_detail::joinPath(path_, it.key()) + ": renamed " +
                          config_detail::joinPath(path_, it.key() + unit) +
                          " (keys name their unit)");
      }
    }
    if (unknown_keys_) unknown_keys_->push_back(config_detail::joinPath(path_, it.key()));
  }
}

namespace {

// A plain YAML scalar is typed by its spelling, as YAML 1.2's core schema does.
nlohmann::json scalarToJson(const YAML::Node& node) {
  const std::string& text = node.Scalar();
  if (node.Tag() == "!") return text;  // quoted: always a string
  if (text == "true" || text == "True" || text == "TRUE") return true;
  if (text == "false" || text == "False" || text == "FALSE") return false;
  if (text == "~" || text == "null" || text == "Null" || text == "NULL") return nullptr;
  if (!text.empty()) {
    char* end = nullptr;
    errno = 0;
    const long long as_int = std::strtoll(text.c_str(), &end, 10);
    if (*end == '\0' && errno == 0) return as_int;
    end = nullptr;
    const double as_double = std::strtod(text.c_str(), &end);
    if (*end == '\0' && std::isfinite(as_double)) return as_double;
    if (text == ".inf" || text == ".Inf") return std::numeric_limits<double>::infinity();
  }
  return text;
}

nlohmann::json yamlToJson(const YAML::Node& node, const std::string& name) {
  switch (node.Type()) {
    case YAML::NodeType::Null:
    case YAML::NodeType::Undefined:
      return nullptr;
    case YAML::NodeType::Scalar:
      return scalarToJson(node);
    case YAML::NodeType::Sequence: {
      nlohmann::json out = nlohmann::json::array();
      for (const auto& item : node) out.push_back(yamlToJson(item, name));
      return out;
    }
    case YAML::NodeType::Map: {
      nlohmann::json out = nlohmann::json::object();
      for (const auto& kv : node) {
        const std::string key = kv.first.as<std::string>();
        if (out.contains(key)) {
          throw ConfigError(name + ": line " + std::to_string(kv.first.Mark().line + 1) +
                            ": duplicate key '" + key + "'");
        }
        out[key] = yamlToJson(kv.second, name);
      }
      return out;
    }
  }
  return nullptr;
}

}  // namespace

nlohmann::json parseYamlAsJson(const std::string& text, const std::string& name) {
  YAML::Node root;
  try {
    root = YAML::Load(text);
  } catch (const YAML::Exception& e) {
    throw ConfigError(name + ": line " + std::to_string(e.mark.line + 1) + ", column " +
                      std::to_string(e.mark.column + 1) + ": " + e.msg);
  }
  return yamlToJson(root, name);
}

nlohmann::json loadYamlAsJson(const std::string& path) {
  std::ifstream in(path);
  if (!in) throw ConfigError(path + ": cannot open file");
  std::stringstream buffer;
  buffer << in.rdbuf();
  return parseYamlAsJson(buffer.str(), path);
}

}  // namespace tacs
