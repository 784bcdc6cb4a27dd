// tacs_draw_world: draws a world file top-down to a PNG.
#include <iostream>
#include <string>

#include "tacs_graphs/sim/world_drawing.h"

namespace {
void printUsage() {
  std::cout << "Usage: tacs_draw_world WORLD.json --out FILE.png [--resolution M]\n"
               "Draws the floors, ground-truth rooms (translucent, labelled), walls (black: full\n"
               "height, blue: half walls and rails), boxes and the robot path (blue, green start,\n"
               "red end) at M metres per pixel (default 0.05).\n";
}
}  // namespace

int main(int argc, char** argv) {
  std::string world_path, out;
  double resolution = 0.05;
  for (int i = 1; i < argc; ++i) {
    const std::string arg = argv[i];
    if (arg == "--help" || arg == "-h") {
      printUsage();
      return 0;
    } else if (arg == "--out" && i + 1 < argc) {
      out = argv[++i];
    } else if (arg == "--resolution" && i + 1 < argc) {
      resolution = std::stod(argv[++i]);
    } else if (world_path.empty() && arg.rfind("--", 0) != 0) {
      world_path = arg;
    } else {
      std::cerr << "tacs_draw_world: unexpected argument '" << arg << "'\n";
      printUsage();
      return 2;
    }
  }
  if (world_path.empty() || out.empty()) {
    printUsage();
    return 2;
  }
  try {
    const tacs::sim::World world = tacs::sim::loadWorld(world_path);
    const tacs::sim::RobotPath path(world, world.sensor.seed, world_path);
    tacs::viz::Canvas canvas = tacs::sim::worldCanvas(world, resolution);
    tacs::sim::drawWorld(world, &path, &canvas);
    canvas.savePng(out);
    std::cout << out << ": " << canvas.width() << "x" << canvas.height() << " px, path "
              << path.length() << " m, " << path.duration() << " s\n";
  } catch (const std::exception& e) {
    std::cerr << "error: " << e.what() << "\n";
    return 1;
  }
  return 0;
}
