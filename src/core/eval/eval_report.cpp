#include "tacs_graphs/eval/eval_report.h"

#include <cmath>
#include <filesystem>
#include <iomanip>
#include <sstream>

#include "tacs_graphs/common/file_io.h"

namespace tacs {

std::vector<EvalRun> planRuns(const std::vector<std::string>& world_paths,
                              const std::vector<EvalMethod>& methods, int trials,
                              const std::string& out_dir) {
  std::vector<EvalRun> runs;
  for (const auto& world : world_paths) {
    const std::string name = std::filesystem::path(world).stem().string();
    for (size_t m = 0; m < methods.size(); ++m) {
      for (int k = 1; k <= trials; ++k) {
        EvalRun r;
        r.world_path = world;
        r.world_name = name;
        r.method_index = m;
        r.trial = k;
        r.seed = static_cast<uint64_t>(k);
        r.dir = out_dir + "/runs/" + name + "/" + methods[m].name + "/trial" + std::to_string(k);
        runs.push_back(r);
      }
    }
  }
  return runs;
}

namespace {

double mean(const std::vector<double>& v) {
  double s = 0.0;
  for (double x : v) s += x;
  return v.empty() ? 0.0 : s / v.size();
}

double stddev(const std::vector<double>& v) {
  const double m = mean(v);
  double s = 0.0;
  for (double x : v) s += (x - m) * (x - m);
  return v.size() < 2 ? 0.0 : std::sqrt(s / v.size());
}

// 97.5 % quantile of Student's t with `dof` >= 1 degrees of freedom (two-sided 95 % interval).
double studentT975(size_t dof) {
  static const double kTable[] = {12.706, 4.303, 3.182, 2.776, 2.571, 2.447, 2.365, 2.306,
                                  2.262,  2.228, 2.201, 2.179, 2.160, 2.145, 2.131, 2.120,
                                  2.110,  2.101, 2.093, 2.086, 2.080, 2.074, 2.069, 2.064,
                                  2.060,  2.056, 2.052, 2.048, 2.045, 2.042};
  constexpr size_t kRows = sizeof(kTable) / sizeof(kTable[0]);
  return dof <= kRows ? kTable[dof - 1] : 1.96;
}

MethodSummary summarizeRuns(std::vector<std::pair<int, RunScores>> trial_runs) {
  MethodSummary s;
  std::vector<RunScores> runs;
  for (auto& [trial, r] : trial_runs) {
    s.ate_by_trial_m[trial] = r.ate_m;
    runs.push_back(std::move(r));
  }
  s.trials = runs.size();
  std::vector<double> ate, odom, path, rooms, loops, pr, ld, fgo, wall, rate;
  std::vector<double> precision, recall, f1, room_dice;
  std::vector<std::vector<RoomRegion>> trial_rooms;
  WallMetrics walls;
  for (const auto& r : runs) {
    walls.walls += r.wall_metrics.walls, walls.correct += r.wall_metrics.correct;
    precision.push_back(r.room_metrics.precision), recall.push_back(r.room_metrics.recall);
    f1.push_back(r.room_metrics.f1), room_dice.push_back(r.room_metrics.mean_dice);
    trial_rooms.push_back(r.room_regions);
    ate.push_back(r.ate_m), odom.push_back(r.odom_ate_m), path.push_back(r.path_m);
    rooms.push_back(r.rooms), loops.push_back(r.loops), ld.push_back(r.t_ld_s);
    fgo.push_back(r.t_fgo_s), wall.push_back(r.wall_time_s);
    if (r.loops > 0) pr.push_back(r.pr_loop);
    if (r.wall_time_s > 0) rate.push_back(r.scans / r.wall_time_s);
  }
  s.ate_m = mean(ate), s.odom_ate_m = mean(odom), s.path_m = mean(path);
  s.n_room = mean(rooms), s.sigma_room = stddev(rooms);
  s.dcs = summarizeTrials(trial_rooms).dcs;
  s.room_precision = mean(precision), s.room_recall = mean(recall), s.room_f1 = mean(f1);
  s.room_dice = mean(room_dice);
  s.wall_precision = walls.precision();
  s.n_loop = mean(loops), s.pr_loop = mean(pr), s.t_ld_s = mean(ld), s.t_fgo_s = mean(fgo);
  s.wall_time_s = mean(wall), s.scans_per_s = mean(rate);
  s.runs = std::move(runs);
  return s;
}

std::string fixed(double v, int digits) {
  std::ostringstream o;
  o << std::fixed << std::setprecision(digits) << v;
  return o.str();
}

// False when the method switches `section` off (`method: none`): it has no rows in that table.
bool runsStage(const EvalMethod& method, const char* section) {
  const auto it = method.overrides.find(section);
  return it == method.overrides.end() || !it->is_object() || it->value("method", "") != "none";
}

}  // namespace

PairedDifference pairedDifference(const std::map<int, double>& a, const std::map<int, double>& b) {
  std::vector<double> d;
  PairedDifference out;
  for (const auto& [trial, va] : a) {
    const auto it = b.find(trial);
    if (it == b.end()) continue;
    d.push_back(it->second - va);
    if (va < it->second) ++out.a_lower;
  }
  out.trials = d.size();
  out.mean = mean(d);
  if (d.size() >= 2) {
    // stddev() divides by n; the interval wants the sample deviation (n - 1): se = sd_n /
    // sqrt(n-1).
    out.ci95 = studentT975(d.size() - 1) * stddev(d) / std::sqrt(static_cast<double>(d.size() - 1));
  }
  return out;
}

std::map<std::string, std::map<size_t, MethodSummary>> summarize(const std::vector<EvalRun>& runs,
                                                                 size_t method_count,
                                                                 std::vector<std::string>* errors) {
  std::map<std::string, std::map<size_t, std::vector<std::pair<int, RunScores>>>> scores;
  for (const auto& r : runs) {
    try {
      scores[r.world_name][r.method_index].emplace_back(r.trial, scoreRunFolder(r.dir));
    } catch (const std::exception& e) {
      if (errors) errors->push_back(e.what());
    }
  }
  std::map<std::string, std::map<size_t, MethodSummary>> out;
  for (auto& [world, by_method] : scores) {
    for (size_t m = 0; m < method_count; ++m) {
      if (by_method.count(m)) out[world][m] = summarizeRuns(std::move(by_method[m]));
    }
  }
  return out;
}

namespace {

using Summaries = std::map<std::string, std::map<size_t, MethodSummary>>;

// Table III: ATE per world and method, the odometry alone first, and the path-weighted mean.
void writeAteTable(std::ostringstream& md, const Summaries& summaries,
                   const std::vector<EvalMethod>& methods) {
  md << "\n## Table III: pose accuracy, ATE (m)\n\n| Method |";
  for (const auto& [world, by_method] : summaries) md << " " << world << " |";
  md << " wATE |\n|---|";
  for (size_t i = 0; i <= summaries.size(); ++i) md << "---|";
  md << "\n";
  // Odometry alone (no backend) first, from the first method's runs.
  for (int row = -1; row < static_cast<int>(methods.size()); ++row) {
    md << "| " << (row < 0 ? std::string("GICP odometry only") : methods[row].label) << " |";
    double weighted = 0.0, length = 0.0;
    for (const auto& [world, by_method] : summaries) {
      const auto it = by_method.find(row < 0 ? 0 : static_cast<size_t>(row));
      if (it == by_method.end()) {
        md << " - |";
        continue;
      }
      const double ate = row < 0 ? it->second.odom_ate_m : it->second.ate_m;
      md << " " << fixed(ate, 4) << " |";
      weighted += ate * it->second.path_m, length += it->second.path_m;
    }
    md << " " << (length > 0 ? fixed(weighted / length, 4) : "-") << " |\n";
  }
}

// Each method's ATE against the first method's on the same trials (paired differences).
void writePairedAteTable(std::ostringstream& md, const Summaries& summaries,
                         const std::vector<EvalMethod>& methods) {
  md << "\n## ATE against " << methods[0].label << ", trial by trial\n\n"
     << "Delta ATE = ATE(method) - ATE(" << methods[0].name
     << ") on the same trial (noise seed), in mm: its mean, the 95 % interval of the mean "
        "(Student t), and the trials where "
     << methods[0].name
     << " is the more accurate. An interval holding 0 is a difference the trials do not "
        "resolve.\n\n"
     << "| World | Method | Delta ATE (mm) | 95 % interval (mm) | " << methods[0].name
     << " better |\n|---|---|---|---|---|\n";
  for (const auto& [world, by_method] : summaries) {
    const auto first = by_method.find(0);
    if (first == by_method.end()) continue;
    for (const auto& [m, s] : by_method) {
      if (m == 0) continue;
      const PairedDifference d = pairedDifference(first->second.ate_by_trial_m, s.ate_by_trial_m);
      if (d.trials == 0) continue;
      md << "| " << world << " | " << methods[m].label << " | " << fixed(1000.0 * d.mean, 2)
         << " | " << fixed(1000.0 * (d.mean - d.ci95), 2) << " .. "
         << fixed(1000.0 * (d.mean + d.ci95), 2) << " | " << d.a_lower << " of " << d.trials
         << " |\n";
    }
  }
}

}  // namespace

void writeEvalReport(const std::string& out_dir, const std::vector<EvalRun>& runs,
                     const std::vector<EvalMethod>& methods) {
  std::vector<std::string> errors;
  const auto summaries = summarize(runs, methods.size(), &errors);
  std::ostringstream md;
  md << "# Evaluation on the simulated worlds\n\n"
     << "Generated by `tacs_eval`; every number is the mean over the trials (noise seeds) of a\n"
     << "world. ATE: RMSE of the optimised keyframe positions after SE(3) alignment.\n\n";
  // One row per world and method that runs `section` ("" : every method): "| world | label | "
  // followed by the cells `cells` gives.
  const auto rows = [&](const char* section, const auto& cells) {
    for (const auto& [world, by_method] : summaries) {
      for (const auto& [m, s] : by_method) {
        if (*section && !runsStage(methods[m], section)) continue;
        md << "| " << world << " | " << methods[m].label << " | " << cells(s) << " |\n";
      }
    }
  };

  md << "## Table I: scene graph consistency\n\n"
     << "DCS: mean over pairs of trials of the Dice of matched rooms' floors over max(N_a, "
        "N_b) (eq. 5).\n\n"
     << "| World | Method | trials | N_room | sigma_room | DCS (%) | t_FGO (s) |\n"
     << "|---|---|---|---|---|---|---|\n";
  rows("rooms", [](const MethodSummary& s) {
    return std::to_string(s.trials) + " | " + fixed(s.n_room, 1) + " | " + fixed(s.sigma_room, 2) +
           " | " + (s.trials > 1 ? fixed(100.0 * s.dcs, 1) : std::string("-")) + " | " +
           fixed(s.t_fgo_s, 2);
  });

  md << "\n## Rooms and walls against ground truth\n\n"
     << "Estimated and ground-truth rooms matched one-to-one by Dice of their 2D floors (the "
        "free space grown up to 1.6 m towards the room's walls, scene_graph/room_floor.h) "
        "(>= 0.5); Dice: mean over ground-truth rooms, unmatched ones count 0. Wall precision: "
        "share of the scene graph's walls lying on a wall of the world (within 10 deg and "
        "0.25 m, half their length over it), not on furniture.\n\n"
     << "| World | Method | precision | recall | F1 | Dice | wall precision |\n"
     << "|---|---|---|---|---|---|---|\n";
  rows("rooms", [](const MethodSummary& s) {
    return fixed(s.room_precision, 2) + " | " + fixed(s.room_recall, 2) + " | " +
           fixed(s.room_f1, 2) + " | " + fixed(s.room_dice, 2) + " | " + fixed(s.wall_precision, 2);
  });

  md << "\n## Table II: loop closure\n\n"
     << "PR_loop: share of accepted loops within 0.3 m and 3 deg of the ground-truth relative pose "
        "(mean over trials with loops).\n\n"
     << "| World | Method | ATE (m) | N_loop | PR_loop | t_LD (s) |\n|---|---|---|---|---|---|\n";
  rows("loop_closure", [](const MethodSummary& s) {
    return fixed(s.ate_m, 4) + " | " + fixed(s.n_loop, 1) + " | " + fixed(s.pr_loop, 2) + " | " +
           fixed(s.t_ld_s, 3);
  });

  writeAteTable(md, summaries, methods);
  if (methods.size() > 1) writePairedAteTable(md, summaries, methods);

  md << "\n## Runs\n\n| World | Method | path (m) | odometry ATE (m) | scans/s | wall time (s) |\n"
     << "|---|---|---|---|---|---|\n";
  rows("", [](const MethodSummary& s) {
    return fixed(s.path_m, 1) + " | " + fixed(s.odom_ate_m, 3) + " | " + fixed(s.scans_per_s, 1) +
           " | " + fixed(s.wall_time_s, 1);
  });

  const auto figures = writeEvalFigures(out_dir, runs, methods, summaries);
  md << "\n## Figures\n\n";
  for (const auto& f : figures) {
    const std::string rel = std::filesystem::relative(f, out_dir).string();
    md << "![" << rel << "](" << rel << ")\n\n";
  }
  if (!errors.empty()) {
    md << "## Runs that could not be scored\n\n";
    for (const auto& e : errors) md << "- " << e << "\n";
  }
  ensureDirectory(out_dir);
  writeFileAtomically(out_dir + "/tables.md", md.str());
}

}  // namespace tacs
