// tacs_prior_eval: scores a session run against a prior map (tacs_offline --prior) on a simulated
// world: the driven distance until relocalization, the session's ATE in the prior's frame with no
// alignment of its own (the prior's frame mapped to the world by the prior run's alignment), and
// how many re-observed rooms got their prior ids.
#include <cmath>
#include <filesystem>
#include <fstream>
#include <iomanip>
#include <iostream>
#include <nlohmann/json.hpp>
#include <string>

#include "tacs_graphs/common/trajectory_io.h"
#include "tacs_graphs/eval/room_metrics.h"
#include "tacs_graphs/eval/trajectory_metrics.h"
#include "tacs_graphs/relocalization/prior_session.h"
#include "tacs_graphs/scene_graph/scene_graph.h"
#include "tacs_graphs/sim/ground_truth.h"
#include "tool_main.h"

namespace {

struct Options {
  std::string prior, session;
  bool json = false;
};

void printUsage() {
  std::cout
      << "Usage: tacs_prior_eval --prior PRIOR_RUN --session SESSION_RUN [--json]\n"
         "PRIOR_RUN: a tacs_offline run folder with ground truth (--world) or a reference\n"
         "(--reference); SESSION_RUN: a run of the same kind with --prior PRIOR_RUN. Prints the\n"
         "session's status, the distance driven until it was placed, its keyframe ATE in the\n"
         "prior's frame without alignment (the prior's frame mapped to the truth by the prior\n"
         "run's SE(3) alignment) and, with ground-truth rooms, the re-observed rooms (found by\n"
         "both runs) that got their prior ids, and the room F1 and wall count of the saved\n"
         "(merged) graph against the prior's.\n"
         "Exit status: 0 done, 1 unreadable input, 2 bad command line.\n";
}

Options parse(int argc, char** argv) {
  Options o;
  for (int i = 1; i < argc; ++i) {
    const std::string arg = argv[i];
    if (arg == "--help" || arg == "-h") {
      printUsage();
      std::exit(0);
    } else if (arg == "--prior" && i + 1 < argc) {
      o.prior = argv[++i];
    } else if (arg == "--session" && i + 1 < argc) {
      o.session = argv[++i];
    } else if (arg == "--json") {
      o.json = true;
    } else {
      throw std::invalid_argument("unexpected argument '" + arg + "'");
    }
  }
  if (o.prior.empty() || o.session.empty()) throw std::invalid_argument("needs --prior, --session");
  return o;
}

std::vector<tacs::RoomRegion> roomsIn(const tacs::SceneGraph& graph, const tacs::Pose3& T) {
  return tacs::floorRegions(graph.transformed(T));
}

/// The run's ground truth (a world's) or reference (--reference, e.g. a real sequence's).
tacs::Trajectory truthOf(const std::string& run) {
  const std::string gt = run + "/ground_truth_tum.txt";
  return tacs::readTum(std::filesystem::exists(gt) ? gt : run + "/reference_tum.txt");
}

int print(const nlohmann::json& out, bool as_json) {
  if (as_json) {
    std::cout << out.dump() << "\n";
  } else {
    std::cout << std::fixed << std::setprecision(3);
    for (const auto& [key, value] : out.items()) std::cout << key << " " << value << "\n";
  }
  return 0;
}

int run(const Options& o) {
  const std::string loc_path = o.session + "/localization.json";
  std::ifstream loc_file(loc_path);
  if (!loc_file) throw std::runtime_error(loc_path + ": cannot open file");
  const nlohmann::json loc = nlohmann::json::parse(loc_file);
  nlohmann::json out;
  out["status"] = loc.at("status");
  out["attempts"] = loc.at("attempts");
  out["rejected_hypotheses"] = loc.at("rejected_hypotheses");
  if (loc.at("status") == "localized") {
    out["distance_m"] = loc.at("first_localization").at("distance_m");
    // The prior's frame in the world, from the prior run's own alignment.
    const tacs::Trajectory prior_gt = truthOf(o.prior);
    const tacs::Pose3 T_world_prior =
        tacs::computeAte(tacs::readTum(o.prior + "/trajectory_tum.txt"), prior_gt, 0.05)
            .T_gt_estimate;
    const tacs::Trajectory session = tacs::readTum(o.session + "/trajectory_tum.txt");
    const tacs::Trajectory session_gt = truthOf(o.session);
    double sum_sq = 0.0, max_err = 0.0;
    const auto pairs = tacs::associateByTime(session, session_gt, 0.05);
    for (const auto& [e, g] : pairs) {
      const double err =
          (T_world_prior * session[e].pose.translation() - session_gt[g].pose.translation()).norm();
      sum_sq += err * err;
      max_err = std::max(max_err, err);
    }
    out["ate_no_alignment_m"] = pairs.empty() ? -1.0 : std::sqrt(sum_sq / pairs.size());
    out["ate_no_alignment_max_m"] = max_err;
    if (!std::filesystem::exists(o.prior + "/ground_truth.json")) return print(out, o.json);
    // Rooms: each run's rooms matched to the ground truth in the world frame.
    const auto truth = tacs::sim::readGroundTruth(o.prior + "/ground_truth.json").rooms;
    const auto prior_rooms = tacs::evaluateRooms(
        roomsIn(tacs::SceneGraph::load(o.prior + "/scene_graph.json"), T_world_prior), truth);
    const auto session_rooms = tacs::evaluateRooms(
        roomsIn(tacs::SceneGraph::load(o.session + "/session_graph.json"), T_world_prior), truth);
    std::map<uint32_t, uint32_t> pairs_by_session;
    for (const auto& p : loc.at("room_pairs")) pairs_by_session[p.at("session")] = p.at("prior");
    int reobserved = 0, kept = 0;
    for (size_t i = 0; i < truth.size(); ++i) {
      const int a = prior_rooms.rooms[i].matched_room, b = session_rooms.rooms[i].matched_room;
      if (a < 0 || b < 0) continue;
      ++reobserved;
      const auto it = pairs_by_session.find(static_cast<uint32_t>(b));
      kept += it != pairs_by_session.end() && it->second == static_cast<uint32_t>(a);
    }
    out["rooms_reobserved"] = reobserved;
    out["rooms_with_prior_id"] = kept;
    out["session_room_f1"] = session_rooms.f1;
    out["prior_room_f1"] = prior_rooms.f1;
    // The saved graph: the merged one (merge mode) should have the prior's rooms, no doubles.
    const tacs::SceneGraph saved = tacs::SceneGraph::load(o.session + "/scene_graph.json");
    out["saved_room_f1"] = tacs::evaluateRooms(roomsIn(saved, T_world_prior), truth).f1;
    const tacs::SceneGraph prior = tacs::SceneGraph::load(o.prior + "/scene_graph.json");
    out["saved_walls"] = saved.wallCount();
    out["prior_walls"] = prior.wallCount();
    // Walls the merge added on a prior wall's plane under looser bounds than its own (20 deg,
    // 0.5 m against 10 deg, 0.3 m): a wall seen twice that the merge did not recognise.
    int doubled = 0;
    for (const auto& [id, wall] : saved.walls) {
      if (prior.walls.count(id) || !wall.is_wall) continue;
      for (const auto& [prior_id, known] : prior.walls) {
        if (tacs::onOnePlane(known, wall, 20.0, 0.5)) {
          ++doubled;
          break;
        }
      }
    }
    out["doubled_walls"] = doubled;
  }
  return print(out, o.json);
}

}  // namespace

int main(int argc, char** argv) {
  return tacs::tools::toolMain("tacs_prior_eval", argc, argv, parse, run, printUsage);
}
