// Configuration plumbing shared by every module.
//
// Each core class has a nested `Config` struct with in-class defaults and two members:
//
//   template <class Visitor> void visit(Visitor& v) { v("voxel_size_m", voxel_size); ... }
//   void validate() const;  // throws ConfigError naming the bad field
//
// `visit` lists the fields once; the same list drives reading from a JSON tree (which is what
// both a YAML file and the ROS parameter server are converted to), writing the effective values
// back out, and reporting keys that no field claimed. Nested Configs are visited recursively.
#pragma once

#include <array>
#include <nlohmann/json.hpp>
#include <stdexcept>
#include <string>
#include <type_traits>
#include <utility>
#include <vector>

namespace tacs {

/// A bad configuration: unreadable file, wrong type, or a value out of range. what() names the
/// file (when known) and the dotted key path, e.g. "config/default.yaml: odometry.voxel_size:
/// must be > 0 (got -1)".
class ConfigError : public std::runtime_error {
 public:
  using std::runtime_error::runtime_error;
};

/// Throws ConfigError("<field>: <reason>") unless `ok`. The helper Config::validate() uses.
void requireConfig(bool ok, const std::string& field, const std::string& reason);

/// The spellings of a mode enum read from a configuration, specialised next to each enum:
///   template <> struct EnumNames<RoomMethod> {
///     static constexpr std::array<std::pair<RoomMethod, const char*>, 3> kNames{{...}};
///   };
/// A Config field of that type is read from (and written as) one of the spellings; any other
/// is a ConfigError listing them.
template <class E>
struct EnumNames;

/// The spelling of `value` ("?" for a value without one).
template <class E>
const char* enumName(E value) {
  for (const auto& [v, name] : EnumNames<E>::kNames) {
    if (v == value) return name;
  }
  return "?";
}

/// "a, b or c": the spellings of E, for messages.
template <class E>
std::string enumChoices() {
  std::string out;
  const auto& names = EnumNames<E>::kNames;
  for (size_t i = 0; i < names.size(); ++i) {
    if (i > 0) out += i + 1 == names.size() ? " or " : ", ";
    out += names[i].second;
  }
  return out;
}

namespace config_detail {

// A visitor that does nothing, used to detect whether a type is a Config (has visit()).
class ConfigReaderProbe {
 public:
  template <class T>
  void operator()(const char*, T&) {}
};

template <class T, class = void>
struct IsVisitable : std::false_type {};
template <class T>
struct IsVisitable<
    T, std::void_t<decltype(std::declval<T&>().visit(std::declval<ConfigReaderProbe&>()))>>
    : std::true_type {};

// Strictly typed scalar reads: nlohmann's get<> would silently turn true into 1.0 or 2.7 into 2.
void readScalar(const nlohmann::json& j, const std::string& path, double* out);
void readScalar(const nlohmann::json& j, const std::string& path, float* out);
void readScalar(const nlohmann::json& j, const std::string& path, int* out);
void readScalar(const nlohmann::json& j, const std::string& path, unsigned* out);
void readScalar(const nlohmann::json& j, const std::string& path, bool* out);
void readScalar(const nlohmann::json& j, const std::string& path, std::string* out);

std::string joinPath(const std::string& path, const std::string& key);

}  // namespace config_detail

/// Visitor that fills a Config from a JSON object and records keys no field claimed.
class ConfigReader {
 public:
  ConfigReader(const nlohmann::json& node, std::string path,
               std::vector<std::string>* unknown_keys);

  template <class T>
  void operator()(const char* key, T& field) {
    claimed_.push_back(key);
    if (!node_.is_object() || !node_.contains(key)) return;  // keep the default
    read(node_.at(key), config_detail::joinPath(path_, key), &field);
  }

  /// Appends the keys of this object that no visited field claimed to the unknown-key list;
  /// throws ConfigError for a key whose field now has a unit suffix (_m, _deg, ...).
  void finish() const;

 private:
  template <class T>
  void read(const nlohmann::json& j, const std::string& path, T* out) {
    if constexpr (config_detail::IsVisitable<T>::value) {
      if (!j.is_object()) throw ConfigError(path + ": expected a mapping of keys");
      ConfigReader nested(j, path, unknown_keys_);
      out->visit(nested);
      nested.finish();
    } else if constexpr (std::is_enum_v<T>) {
      std::string name;
      config_detail::readScalar(j, path, &name);
      for (const auto& [value, spelling] : EnumNames<T>::kNames) {
        if (name == spelling) {
          *out = value;
          return;
        }
      }
      throw ConfigError(path + ": must be " + enumChoices<T>() + " (got \"" + name + "\")");
    } else {
      config_detail::readScalar(j, path, out);
    }
  }
  template <class T>
  void read(const nlohmann::json& j, const std::string& path, std::vector<T>* out) {
    if (!j.is_array()) throw ConfigError(path + ": expected a list, got " + j.dump());
    out->assign(j.size(), T{});
    for (size_t i = 0; i < j.size(); ++i) {
      read(j[i], path + "[" + std::to_string(i) + "]", &(*out)[i]);
    }
  }

  const nlohmann::json& node_;
  std::string path_;
  std::vector<std::string>* unknown_keys_;
  std::vector<std::string> claimed_;
};

/// Visitor that writes a Config's effective values into a JSON object.
class ConfigWriter {
 public:
  explicit ConfigWriter(nlohmann::json* out) : out_(out) {}

  template <class T>
  void operator()(const char* key, const T& field) {
    if constexpr (config_detail::IsVisitable<T>::value) {
      nlohmann::json nested = nlohmann::json::object();
      ConfigWriter writer(&nested);
      const_cast<T&>(field).visit(writer);  // visit() only reads through this visitor
      (*out_)[key] = nested;
    } else if constexpr (std::is_enum_v<T>) {
      (*out_)[key] = enumName(field);
    } else {
      (*out_)[key] = field;
    }
  }

 private:
  nlohmann::json* out_;
};

/// Reads `config` from `j` (missing keys keep their defaults), then validates it. `where` prefixes
/// every error (a file name, or "ROS parameter /tacs"); unknown keys are appended as dotted paths.
template <class Config>
void configFromJson(const nlohmann::json& j, const std::string& where, Config* config,
                    std::vector<std::string>* unknown_keys) {
  try {
    if (!j.is_object() && !j.is_null()) throw ConfigError("top level: expected a mapping of keys");
    static const nlohmann::json kEmpty = nlohmann::json::object();
    ConfigReader reader(j.is_null() ? kEmpty : j, "", unknown_keys);
    config->visit(reader);
    reader.finish();
    config->validate();
  } catch (const ConfigError& e) {
    throw ConfigError(where + ": " + e.what());
  }
}

/// The effective values of `config` as JSON (logged by nodes, written to run folders).
template <class Config>
nlohmann::json configToJson(const Config& config) {
  nlohmann::json out = nlohmann::json::object();
  ConfigWriter writer(&out);
  const_cast<Config&>(config).visit(writer);
  return out;
}

/// Parses a YAML file into JSON. Plain scalars become bool, integer or float when they read as
/// one; quoted scalars stay strings. Throws ConfigError "<path>: line L, column C: <reason>".
nlohmann::json loadYamlAsJson(const std::string& path);

/// Same, from YAML text; `name` is used in error messages.
nlohmann::json parseYamlAsJson(const std::string& text, const std::string& name);

}  // namespace tacs
