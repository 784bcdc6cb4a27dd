#include <algorithm>
#include <cmath>
#include <iomanip>
#include <sstream>

#include "tacs_graphs/common/file_io.h"
#include "tacs_graphs/eval/eval_report.h"
#include "tacs_graphs/sim/world_drawing.h"
#include "tacs_graphs/viz/scene_graph_drawing.h"

namespace tacs {
namespace {

/// The world with its ground-truth rooms, the estimated scene graph of trial 1 of `method` moved
/// onto the world by the trajectory alignment.
std::string drawWorldFigure(const std::string& out_dir, const EvalRun& run,
                            const EvalMethod& method, const RunScores& scores) {
  const sim::World world = sim::loadWorld(run.world_path);
  viz::Canvas canvas = sim::worldCanvas(world, 0.05);
  sim::drawWorld(world, nullptr, &canvas);
  viz::drawSceneGraph(transformSceneGraph(scores.graph, scores.T_world_map), nullptr, &canvas);
  canvas.drawTextPx(10, 10, run.world_name + ": " + method.label, {0, 0, 0, 255}, 3);
  const std::string path = out_dir + "/figures/" + run.world_name + "_" + method.name + ".png";
  canvas.savePng(path);
  return path;
}

std::string label(double v, int digits) {
  std::ostringstream o;
  o << std::fixed << std::setprecision(digits) << v;
  return o.str();
}

/// ATE against t_LD, one marker per (world, method), as the paper's Fig. 7.
std::string drawAteVsLoopTime(const std::string& out_dir, const std::vector<EvalMethod>& methods,
                              const std::map<std::string, std::map<size_t, MethodSummary>>& sums) {
  double max_ate = 0.01, max_ld = 0.01;
  for (const auto& [world, by_method] : sums) {
    for (const auto& [m, s] : by_method) {
      max_ate = std::max(max_ate, s.ate_m), max_ld = std::max(max_ld, s.t_ld_s);
    }
  }
  // Plot coordinates: x = t_LD scaled to [0, 10], y = ATE scaled to [0, 6].
  const double sx = 10.0 / (1.1 * max_ld), sy = 6.0 / (1.1 * max_ate);
  viz::Canvas canvas({-1.5, -1.2}, {13.5, 7.0}, 0.01);
  const viz::Rgba black{0, 0, 0, 255};
  canvas.drawLine({0, 0}, {10.5, 0}, black, 2.0);
  canvas.drawLine({0, 0}, {0, 6.5}, black, 2.0);
  for (int i = 0; i <= 4; ++i) {
    const double x = i * 2.5, y = i * 1.5;
    canvas.drawLine({x, 0}, {x, -0.1}, black, 2.0);
    canvas.drawText({x - 0.2, -0.2}, label(x / sx, 2), black, 2);
    canvas.drawLine({0, y}, {-0.1, y}, black, 2.0);
    canvas.drawText({-1.45, y + 0.1}, label(y / sy, 3), black, 2);
  }
  canvas.drawText({4.0, -0.7}, "t_LD (s)", black, 3);
  canvas.drawText({0.2, 6.9}, "ATE (m)", black, 3);
  for (size_t m = 0; m < methods.size(); ++m) {
    const viz::Rgba c = viz::roomColor(static_cast<uint32_t>(m), 255);
    canvas.fillCircle({10.8, 6.5 - 0.45 * m}, 0.12, c);
    canvas.drawText({11.0, 6.6 - 0.45 * m}, methods[m].name, black, 2);
    for (const auto& [world, by_method] : sums) {
      const auto it = by_method.find(m);
      if (it == by_method.end()) continue;
      canvas.fillCircle({it->second.t_ld_s * sx, it->second.ate_m * sy}, 0.12, c);
    }
  }
  const std::string path = out_dir + "/figures/ate_vs_t_ld.png";
  canvas.savePng(path);
  return path;
}

}  // namespace

std::vector<std::string> writeEvalFigures(
    const std::string& out_dir, const std::vector<EvalRun>& runs,
    const std::vector<EvalMethod>& methods,
    const std::map<std::string, std::map<size_t, MethodSummary>>& summaries) {
  ensureDirectory(out_dir + "/figures");
  std::vector<std::string> paths;
  for (const auto& run : runs) {
    if (run.trial != 1) continue;
    const auto w = summaries.find(run.world_name);
    if (w == summaries.end()) continue;
    const auto m = w->second.find(run.method_index);
    if (m == w->second.end() || m->second.runs.empty()) continue;
    paths.push_back(drawWorldFigure(out_dir, run, methods[run.method_index], m->second.runs[0]));
  }
  if (!summaries.empty()) paths.push_back(drawAteVsLoopTime(out_dir, methods, summaries));
  return paths;
}

}  // namespace tacs
