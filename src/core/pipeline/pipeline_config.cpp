#include "tacs_graphs/pipeline/pipeline_config.h"

namespace tacs {

void PipelineConfig::validate() const {
  frames.validate();
  odometry.validate();
  walls.validate();
  backend.validate();
  traversability.validate();
  map_export.validate();
  rooms.validate();
  loop_closure.validate();
  relocalization.validate();
}

LoadedPipelineConfig loadPipelineConfig(const std::string& yaml_path) {
  LoadedPipelineConfig loaded;
  configFromJson(loadYamlAsJson(yaml_path), yaml_path, &loaded.config, &loaded.unknown_keys);
  return loaded;
}

}  // namespace tacs
