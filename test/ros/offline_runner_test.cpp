// tacs_offline run as a user runs it: a fault (an unwritable --out, a folder of something else,
// Ctrl-C) gives an `error:` line and exit 1 and leaves --out as it was; a run replaces a former
// run's folder whole; a second session relocalizes in a first one's folder (--prior) and never
// changes it.
#include <gtest/gtest.h>
#include <sys/wait.h>
#include <unistd.h>

#include <chrono>
#include <csignal>
#include <cstdio>
#include <filesystem>
#include <fstream>
#include <map>
#include <nlohmann/json.hpp>
#include <string>
#include <thread>

#include "common/test_paths.h"
#include "tacs_graphs/ros/sim_bag_writer.h"
#include "tacs_graphs/scene_graph/scene_graph.h"

namespace tacs {
namespace {

namespace fs = std::filesystem;

struct Outcome {
  int exit_status = -1;
  std::string output;  // stdout and stderr
};

// Runs `tool` with `args`; with interrupt_after_s > 0 it gets a SIGINT then.
Outcome runTool(const std::string& tool, const std::string& args, double interrupt_after_s = 0.0) {
  const fs::path log =
      fs::temp_directory_path() / ("tacs_offline_test_" + std::to_string(getpid()));
  const std::string command = tool + " " + args + " > " + log.string() + " 2>&1";
  const pid_t pid = fork();
  if (pid == 0) {
    setpgid(0, 0);
    execl("/bin/sh", "sh", "-c", ("exec " + command).c_str(), static_cast<char*>(nullptr));
    _exit(127);
  }
  if (interrupt_after_s > 0.0) {
    std::this_thread::sleep_for(std::chrono::duration<double>(interrupt_after_s));
    kill(pid, SIGINT);
  }
  int status = 0;
  waitpid(pid, &status, 0);
  Outcome out;
  out.exit_status = WIFEXITED(status) ? WEXITSTATUS(status) : -1;
  std::ifstream in(log);
  out.output.assign(std::istreambuf_iterator<char>(in), {});
  fs::remove(log);
  return out;
}

Outcome runOffline(const std::string& args, double interrupt_after_s = 0.0) {
  return runTool(TACS_OFFLINE_BIN, args + " --quiet", interrupt_after_s);
}

class OfflineRunner : public ::testing::Test {
 protected:
  void SetUp() override {
    root_ = fs::temp_directory_path() /
            ("tacs_offline_runner_" + std::to_string(getpid()) + "_" +
             ::testing::UnitTest::GetInstance()->current_test_info()->name());
    fs::remove_all(root_);
    fs::create_directories(root_);
    world_ = "--world " + test::sourceDir() + "/worlds/smoke.json";
  }
  void TearDown() override { fs::remove_all(root_); }
  size_t entries(const fs::path& dir) const {
    return static_cast<size_t>(std::distance(fs::directory_iterator(dir), {}));
  }
  fs::path root_;
  std::string world_;
};

TEST_F(OfflineRunner, AnUnwritableOutFailsAtOnceAndTouchesNothing) {
  std::ofstream(root_ / "file") << "keep";
  for (const fs::path& out : {root_ / "file", root_ / "file" / "run"}) {
    SCOPED_TRACE(out);
    const Outcome r = runOffline(world_ + " --out " + out.string());
    EXPECT_EQ(r.exit_status, 1);
    EXPECT_NE(r.output.find("error: cannot write the run to " + out.string()), std::string::npos)
        << r.output;
    // Before the first scan: the world's 197 scans take seconds.
    EXPECT_EQ(r.output.find("scans ("), std::string::npos) << r.output;
  }
  EXPECT_EQ(entries(root_), 1u);
}

TEST_F(OfflineRunner, AFolderOfSomethingElseIsNeverReplaced) {
  fs::create_directories(root_ / "notes");
  std::ofstream(root_ / "notes" / "todo.txt") << "keep";
  const Outcome r = runOffline(world_ + " --out " + (root_ / "notes").string());
  EXPECT_EQ(r.exit_status, 1);
  EXPECT_NE(r.output.find("error: cannot write the run to"), std::string::npos) << r.output;
  EXPECT_EQ(entries(root_ / "notes"), 1u);
}

TEST_F(OfflineRunner, ARunReplacesAFormerRunWholeAndCtrlCLeavesItAsItWas) {
  const fs::path out = root_ / "run";
  fs::create_directories(out);
  std::ofstream(out / "reference_tum.txt") << "a former run's\n";
  const Outcome done = runOffline(world_ + " --out " + out.string());
  ASSERT_EQ(done.exit_status, 0) << done.output;
  EXPECT_FALSE(fs::exists(out / "reference_tum.txt"));  // not left beside the new run
  for (const char* f : {"trajectory_tum.txt", "scene_graph.json", "map.bt", "ground_truth.json"}) {
    EXPECT_TRUE(fs::exists(out / f)) << f;
  }
  EXPECT_EQ(entries(root_), 1u);  // nothing staged left beside it
  const auto stamp = fs::last_write_time(out / "trajectory_tum.txt");
  // Ctrl-C in the middle of the next run (a world of 856 scans, far from done after a second): an
  // error line, the finished run untouched.
  const Outcome stopped = runOffline(
      "--world " + test::sourceDir() + "/worlds/lab_room.json --out " + out.string(), 1.0);
  EXPECT_EQ(stopped.exit_status, 1);
  EXPECT_NE(stopped.output.find("error: interrupted"), std::string::npos) << stopped.output;
  EXPECT_EQ(fs::last_write_time(out / "trajectory_tum.txt"), stamp);
  EXPECT_EQ(entries(root_), 1u);
}

size_t occurrences(const std::string& text, const std::string& what) {
  size_t n = 0;
  for (size_t at = text.find(what); at != std::string::npos; at = text.find(what, at + 1)) ++n;
  return n;
}

TEST_F(OfflineRunner, ABagWithoutAUsableScanFailsAndWritesNothing) {
  // Six scans whose returns all lie at the sensor (a driver's "no return" points): each is
  // rejected for the same reason, reported once, and no run folder appears.
  const fs::path bag = root_ / "origin.bag";
  {
    SimBagWriter writer(bag.string(), Pose3::Identity(), SimBagWriter::Options{});
    sim::SimScan scan;
    scan.points.assign(3000, {0.f, 0.f, 0.f, 10.f, 0, 0.0f});
    for (int i = 0; i < 6; ++i) {
      scan.stamp = 1000.0 + 0.1 * i;
      writer.write(scan);
    }
  }
  const fs::path out = root_ / "run";
  const Outcome r =
      runOffline("--bag " + bag.string() + " --topic /velodyne_points --out " + out.string());
  EXPECT_EQ(r.exit_status, 1);
  EXPECT_NE(r.output.find("error: no usable scan among 6"), std::string::npos) << r.output;
  EXPECT_EQ(occurrences(r.output, "rejected:"), 1u) << r.output;
  EXPECT_FALSE(fs::exists(out));
  EXPECT_EQ(entries(root_), 1u);  // the bag alone: nothing staged left beside it
}

TEST_F(OfflineRunner, TacsEvalKeepsItsOwnFilesBesideEachRunFolder) {
  // tacs_eval hands each run folder to tacs_offline, which replaces it whole: the run's config,
  // log and done mark lie beside it.
  const Outcome r =
      runTool(TACS_EVAL_BIN, "--worlds " + test::sourceDir() +
                                 "/worlds/smoke.json --trials 1 --out " + root_.string());
  ASSERT_EQ(r.exit_status, 0) << r.output;
  EXPECT_NE(r.output.find("0 failed"), std::string::npos) << r.output;
  EXPECT_TRUE(fs::exists(root_ / "tables.md"));
  const fs::path trial = root_ / "runs" / "smoke" / "tacs" / "trial1";
  EXPECT_TRUE(fs::exists(trial / "scene_graph.json"));
  for (const char* beside : {".config.json", ".log", ".done"}) {
    EXPECT_TRUE(fs::exists(trial.string() + beside)) << beside;
  }
}

std::string fileBytes(const fs::path& file) {
  std::ifstream in(file, std::ios::binary);
  return std::string(std::istreambuf_iterator<char>(in), {});
}

std::map<std::string, std::string> folderBytes(const fs::path& dir) {
  std::map<std::string, std::string> files;
  for (const auto& e : fs::directory_iterator(dir))
    files[e.path().filename()] = fileBytes(e.path());
  return files;
}

TEST_F(OfflineRunner, ASecondSessionRelocalizesInTheFirstsMapAndNeverChangesIt) {
  const fs::path prior = root_ / "prior", merged = root_ / "merged", local = root_ / "local";
  ASSERT_EQ(runOffline(world_ + " --seed 1 --out " + prior.string()).exit_status, 0);
  const auto before = folderBytes(prior);
  // The second session starts at another waypoint, with other noise.
  const std::string second = world_ + " --seed 2 --start-waypoint 4 --prior " + prior.string();
  const Outcome m = runOffline(second + " --out " + merged.string());
  ASSERT_EQ(m.exit_status, 0) << m.output;
  EXPECT_NE(m.output.find("[tacs_offline] localized after"), std::string::npos) << m.output;
  const auto loc = nlohmann::json::parse(fileBytes(merged / "localization.json"));
  EXPECT_EQ(loc["status"], "localized");
  EXPECT_EQ(loc["mode"], "merge");
  EXPECT_FALSE(loc["room_pairs"].empty());
  // Merged: the prior's rooms are all there, under their ids, and no new room doubles one.
  const SceneGraph prior_graph = SceneGraph::load((prior / "scene_graph.json").string());
  const SceneGraph merged_graph = SceneGraph::load((merged / "scene_graph.json").string());
  for (const auto& [id, room] : prior_graph.rooms) EXPECT_TRUE(merged_graph.rooms.count(id)) << id;
  const size_t session_rooms =
      SceneGraph::load((merged / "session_graph.json").string()).rooms.size();
  EXPECT_EQ(merged_graph.rooms.size(),
            prior_graph.rooms.size() + session_rooms - loc["room_pairs"].size());
  EXPECT_GT(merged_graph.keyframes.size(), prior_graph.keyframes.size());

  const Outcome l = runOffline(second + " --localize-only --out " + local.string());
  ASSERT_EQ(l.exit_status, 0) << l.output;
  EXPECT_EQ(fileBytes(local / "scene_graph.json"), fileBytes(prior / "scene_graph.json"));
  EXPECT_EQ(nlohmann::json::parse(fileBytes(local / "localization.json"))["mode"], "localize_only");
  EXPECT_EQ(folderBytes(prior), before);  // the prior is only ever read
}

TEST_F(OfflineRunner, ABadPriorFailsBeforeTheFirstScanNamingTheFile) {
  const fs::path prior = root_ / "prior", out = root_ / "run";
  fs::create_directories(prior);
  std::ofstream(prior / "scene_graph.json") << "{\"format\": \"tacs_graphs/scene_graph\", ";
  const Outcome r = runOffline(world_ + " --prior " + prior.string() + " --out " + out.string());
  EXPECT_EQ(r.exit_status, 1);
  EXPECT_NE(r.output.find("error: " + (prior / "scene_graph.json").string() + ": not valid JSON"),
            std::string::npos)
      << r.output;
  EXPECT_EQ(r.output.find("scans ("), std::string::npos) << r.output;
  EXPECT_FALSE(fs::exists(out));
  // --out may not be the prior's own folder.
  const Outcome same =
      runOffline(world_ + " --prior " + prior.string() + " --out " + prior.string());
  EXPECT_EQ(same.exit_status, 1);
  EXPECT_NE(same.output.find("is the prior's folder"), std::string::npos) << same.output;
  EXPECT_EQ(fileBytes(prior / "scene_graph.json"), "{\"format\": \"tacs_graphs/scene_graph\", ");
}

TEST_F(OfflineRunner, ASessionInAnotherBuildingIsNotLocalized) {
  const fs::path prior = root_ / "prior", out = root_ / "run";
  ASSERT_EQ(runOffline(world_ + " --out " + prior.string()).exit_status, 0);
  const Outcome r =
      runOffline("--world " + test::sourceDir() + "/worlds/lab_room.json --duration 40 --prior " +
                 prior.string() + " --out " + out.string());
  ASSERT_EQ(r.exit_status, 0) << r.output;
  EXPECT_NE(r.output.find("[tacs_offline] not_localized"), std::string::npos) << r.output;
  const auto loc = nlohmann::json::parse(fileBytes(out / "localization.json"));
  EXPECT_EQ(loc["status"], "not_localized");
  EXPECT_GE(loc["attempts"].get<int>(), 1);
  EXPECT_FALSE(loc.contains("T_prior_session"));
}

}  // namespace
}  // namespace tacs
