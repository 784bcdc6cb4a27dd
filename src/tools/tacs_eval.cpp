// tacs_eval: runs K trials (noise seeds) of every method on every world with tacs_offline, scores
// the run folders and writes the paper's tables (markdown) and figures (PNG). Finished runs are
// kept and skipped on the next call, so an interrupted evaluation resumes.
#include <unistd.h>

#include <algorithm>
#include <atomic>
#include <filesystem>
#include <fstream>
#include <iomanip>
#include <iostream>
#include <mutex>
#include <sstream>
#include <string>
#include <thread>
#include <vector>

#include "tacs_graphs/common/config.h"
#include "tacs_graphs/common/file_io.h"
#include "tacs_graphs/common/timing.h"
#include "tacs_graphs/eval/eval_report.h"
#include "tool_main.h"

namespace fs = std::filesystem;

namespace {

void printUsage() {
  std::cout
      << "Usage: tacs_eval [--worlds A.json,B.json,...] [--methods YAML] [--config YAML]\n"
         "                 [--trials K] [--jobs N] [--duration S] --out DIR\n"
         "Runs every method of YAML (default config/eval/methods.yaml) on every world (default:\n"
         "every worlds/*.json but smoke) K times (noise seeds 1..K, default 5), N runs at a time\n"
         "(default: the number of cores), and writes DIR/tables.md and DIR/figures/*.png; run\n"
         "folders go to DIR/runs/<world>/<method>/trial<k>/ and finished ones are not run again.\n"
         "--config YAML  base configuration the methods change (default config/default.yaml)\n"
         "--duration S   simulate only the first S seconds of each world (quick checks)\n";
}

struct Options {
  std::vector<std::string> worlds;
  std::string methods, config, out;
  int trials = 5;
  int jobs = static_cast<int>(std::max(1u, std::thread::hardware_concurrency()));
  double duration_s = 0.0;
};

/// The source tree (worlds/, config/): $TACS_SOURCE_DIR, else where the tool was built from.
std::string sourceDir() {
  const char* env = std::getenv("TACS_SOURCE_DIR");
  return env ? env : TACS_SOURCE_DIR;
}

/// The folder of this executable, read once at start (a rebuild may replace the file later).
const std::string& selfDir() {
  static const std::string dir = fs::canonical("/proc/self/exe").parent_path().string();
  return dir;
}

Options parse(int argc, char** argv) {
  Options o;
  o.methods = sourceDir() + "/config/eval/methods.yaml";
  o.config = sourceDir() + "/config/default.yaml";
  for (int i = 1; i < argc; ++i) {
    const std::string arg = argv[i];
    const bool has_value = i + 1 < argc;
    if (arg == "--help" || arg == "-h") {
      printUsage();
      std::exit(0);
    } else if (arg == "--worlds" && has_value) {
      std::stringstream list(argv[++i]);
      for (std::string w; std::getline(list, w, ',');) {
        if (!w.empty()) o.worlds.push_back(w);
      }
    } else if (arg == "--methods" && has_value) {
      o.methods = argv[++i];
    } else if (arg == "--config" && has_value) {
      o.config = argv[++i];
    } else if (arg == "--trials" && has_value) {
      o.trials = std::stoi(argv[++i]);
    } else if (arg == "--jobs" && has_value) {
      o.jobs = std::stoi(argv[++i]);
    } else if (arg == "--duration" && has_value) {
      o.duration_s = std::stod(argv[++i]);
    } else if (arg == "--out" && has_value) {
      o.out = argv[++i];
    } else {
      throw std::invalid_argument("unexpected argument '" + arg + "'");
    }
  }
  if (o.out.empty()) throw std::invalid_argument("--out is required");
  if (o.trials < 1 || o.jobs < 1) throw std::invalid_argument("--trials and --jobs must be >= 1");
  if (o.worlds.empty()) {
    for (const auto& entry : fs::directory_iterator(sourceDir() + "/worlds")) {
      if (entry.path().extension() == ".json" && entry.path().stem() != "smoke") {
        o.worlds.push_back(entry.path().string());
      }
    }
    std::sort(o.worlds.begin(), o.worlds.end());
  }
  return o;
}

std::string shellQuote(const std::string& s) {
  std::string q = "'";
  for (char c : s) q += c == '\'' ? std::string("'\\''") : std::string(1, c);
  return q + "'";
}

/// Runs one experiment through tacs_offline; true when its run folder is complete. The run's
/// configuration, log and done mark lie beside its folder (<dir>.config.json, .log, .done):
/// tacs_offline replaces the folder whole.
bool runOne(const tacs::EvalRun& run, const tacs::EvalMethod& method, const nlohmann::json& base,
            const Options& o, std::string* error) {
  fs::create_directories(fs::path(run.dir).parent_path());
  // Runs share the cores: one thread each, so N jobs use N cores.
  nlohmann::json one_thread;
  one_thread["odometry"]["gicp"]["num_threads"] = 1;
  const nlohmann::json config =
      tacs::mergeJson(tacs::mergeJson(base, method.overrides), one_thread);
  tacs::writeFileAtomically(run.dir + ".config.json", config.dump(2) + "\n");
  std::string cmd =
      "OMP_WAIT_POLICY=passive OMP_NUM_THREADS=1 " + shellQuote(selfDir() + "/tacs_offline") +
      " --quiet --world " + shellQuote(run.world_path) + " --seed " + std::to_string(run.seed) +
      " --config " + shellQuote(run.dir + ".config.json") + " --out " + shellQuote(run.dir);
  if (o.duration_s > 0) cmd += " --duration " + std::to_string(o.duration_s);
  cmd += " > " + shellQuote(run.dir + ".log") + " 2>&1";
  if (std::system(cmd.c_str()) != 0) {
    *error = "tacs_offline failed, see " + run.dir + ".log";
    return false;
  }
  std::ofstream(run.dir + ".done") << "ok\n";
  return true;
}

void progress(size_t done, size_t total, size_t skipped, double elapsed_s) {
  const int width = 30;
  const int filled = total ? static_cast<int>(width * done / total) : width;
  const size_t ran = done - skipped;
  const double eta = ran ? elapsed_s / ran * (total - done) : 0.0;
  std::cerr << "\r[tacs_eval] [" << std::string(filled, '#') << std::string(width - filled, '.')
            << "] " << done << "/" << total << " runs (" << skipped << " reused), " << std::fixed
            << std::setprecision(0) << elapsed_s << " s, eta " << eta << " s   " << std::flush;
}

int run(const Options& o) {
  const std::string offline = selfDir() + "/tacs_offline";
  if (!fs::exists(offline)) throw std::runtime_error(offline + ": not found (build tacs_offline)");
  const std::vector<tacs::EvalMethod> methods = tacs::loadEvalMethods(o.methods);
  const nlohmann::json base = tacs::loadYamlAsJson(o.config);
  const std::vector<tacs::EvalRun> runs = tacs::planRuns(o.worlds, methods, o.trials, o.out);
  std::vector<size_t> todo;
  for (size_t i = 0; i < runs.size(); ++i) {
    if (!fs::exists(runs[i].dir + ".done")) todo.push_back(i);
  }
  const size_t skipped = runs.size() - todo.size();
  std::atomic<size_t> next{0}, done{skipped};
  std::mutex mutex;
  std::vector<std::string> failures;
  tacs::Stopwatch watch;
  progress(done, runs.size(), skipped, 0.0);
  auto worker = [&] {
    for (size_t k; (k = next++) < todo.size();) {
      const tacs::EvalRun& r = runs[todo[k]];
      std::string error;
      const bool ok = runOne(r, methods[r.method_index], base, o, &error);
      std::lock_guard<std::mutex> lock(mutex);
      if (!ok) failures.push_back(error);
      progress(++done, runs.size(), skipped, watch.elapsedMs() / 1e3);
    }
  };
  std::vector<std::thread> workers;
  for (int j = 0; j < o.jobs; ++j) workers.emplace_back(worker);
  for (auto& w : workers) w.join();
  std::cerr << "\n";
  for (const auto& f : failures) std::cerr << "[tacs_eval] " << f << "\n";
  tacs::writeEvalReport(o.out, runs, methods);
  std::cout << "[tacs_eval] " << runs.size() << " runs (" << skipped << " reused, "
            << failures.size() << " failed) in " << std::fixed << std::setprecision(0)
            << watch.elapsedMs() / 1e3 << " s -> " << o.out << "/tables.md\n";
  return failures.empty() ? 0 : 1;
}

}  // namespace

int main(int argc, char** argv) {
  return tacs::tools::toolMain("tacs_eval", argc, argv, parse, run, printUsage);
}
