// tacs_config: loads a configuration file, validates it and prints the effective values.
#include <iostream>
#include <string>

#include "tacs_graphs/pipeline/pipeline_config.h"

namespace {
void printUsage() {
  std::cout << "Usage: tacs_config [--config FILE]\n"
               "Loads FILE (default: the built-in defaults), validates every section, reports\n"
               "unknown keys and prints the effective configuration as JSON.\n"
               "Exit status: 0 valid, 1 invalid, 2 bad command line.\n";
}
}  // namespace

int main(int argc, char** argv) {
  std::string path;
  for (int i = 1; i < argc; ++i) {
    const std::string arg = argv[i];
    if (arg == "--help" || arg == "-h") {
      printUsage();
      return 0;
    } else if (arg == "--config" && i + 1 < argc) {
      path = argv[++i];
    } else {
      std::cerr << "tacs_config: unexpected argument '" << arg << "'\n";
      printUsage();
      return 2;
    }
  }
  try {
    tacs::LoadedPipelineConfig loaded;
    if (!path.empty()) loaded = tacs::loadPipelineConfig(path);
    for (const auto& key : loaded.unknown_keys) {
      std::cerr << "warning: " << path << ": unknown key '" << key << "' is ignored\n";
    }
    std::cout << tacs::configToJson(loaded.config).dump(2) << "\n";
  } catch (const tacs::ConfigError& e) {
    std::cerr << "error: " << e.what() << "\n";
    return 1;
  }
  return 0;
}
