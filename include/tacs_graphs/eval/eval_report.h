// The report of tacs_eval: the run plan (world x method x trial), the markdown tables in the
// layout of the paper's Tables I-III plus ground-truth room scores, and the figures.
#pragma once

#include <cstdint>
#include <map>
#include <optional>
#include <string>
#include <vector>

#include "tacs_graphs/eval/experiment.h"

namespace tacs {

struct EvalRun {
  std::string world_path;
  std::string world_name;  // file stem
  size_t method_index = 0;
  int trial = 0;      // 1..K
  uint64_t seed = 0;  // simulator noise seed of the trial
  std::string dir;    // <out>/runs/<world>/<method>/trial<k>
};

/// Every (world, method, trial), trial k with seed k.
std::vector<EvalRun> planRuns(const std::vector<std::string>& world_paths,
                              const std::vector<EvalMethod>& methods, int trials,
                              const std::string& out_dir);

/// Mean and spread of the scores of one method on one world.
struct MethodSummary {
  size_t trials = 0;
  double ate_m = 0.0, odom_ate_m = 0.0, path_m = 0.0;
  double n_room = 0.0, sigma_room = 0.0, dcs = 0.0;  // Table I (paper eq. 5)
  double room_precision = 0.0, room_recall = 0.0, room_f1 = 0.0, room_dice = 0.0;
  double wall_precision = 0.0;  // of the walls, over all trials' walls (eval/wall_metrics.h)
  double n_loop = 0.0, pr_loop = 0.0, t_ld_s = 0.0, t_fgo_s = 0.0;
  double wall_time_s = 0.0, scans_per_s = 0.0;
  std::vector<RunScores> runs;
  std::map<int, double> ate_by_trial_m;  // trial -> ATE, for comparisons on the same noise seed
};

/// Per-trial difference b - a over the trials both hold (the same noise seed, so the world's
/// noise cancels): its mean, the half width of the mean's 95 % Student-t interval (0 below two
/// trials), and the trials where a is the lower.
struct PairedDifference {
  size_t trials = 0;
  double mean = 0.0;
  double ci95 = 0.0;
  size_t a_lower = 0;
};
PairedDifference pairedDifference(const std::map<int, double>& a, const std::map<int, double>& b);

/// Summaries by world name, then by method index; runs without a finished folder are left out.
std::map<std::string, std::map<size_t, MethodSummary>> summarize(const std::vector<EvalRun>& runs,
                                                                 size_t method_count,
                                                                 std::vector<std::string>* errors);

/// Writes <out>/tables.md and <out>/figures/*.png.
void writeEvalReport(const std::string& out_dir, const std::vector<EvalRun>& runs,
                     const std::vector<EvalMethod>& methods);

/// Figures: each world top-down with the first method's rooms over the ground truth, and ATE
/// against t_LD (the paper's Fig. 7). Returns the written paths.
std::vector<std::string> writeEvalFigures(
    const std::string& out_dir, const std::vector<EvalRun>& runs,
    const std::vector<EvalMethod>& methods,
    const std::map<std::string, std::map<size_t, MethodSummary>>& summaries);

}  // namespace tacs
