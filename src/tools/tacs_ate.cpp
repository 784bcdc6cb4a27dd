// tacs_ate: absolute trajectory error of a TUM trajectory (e.g. the backend's trajectory_tum.txt)
// against a reference, after SE(3) alignment (eval/trajectory_metrics.h, as `evo_ape -a`).
#include <iostream>
#include <string>

#include "tacs_graphs/common/trajectory_io.h"
#include "tacs_graphs/eval/trajectory_metrics.h"
#include "tool_main.h"

namespace {

struct Options {
  std::string estimate, reference;
  double max_dt = 0.05;
};

void printUsage() {
  std::cout
      << "Usage: tacs_ate ESTIMATE_TUM REFERENCE_TUM [--max-dt S]\n"
         "Prints 'ATE <rmse> m (mean, max, N poses)' of ESTIMATE against REFERENCE after\n"
         "SE(3) alignment; poses are paired by nearest stamp within S seconds (0.05).\n"
         "Exit status: 0 done, 1 unreadable file or fewer than 3 pairs, 2 bad command line.\n";
}

Options parse(int argc, char** argv) {
  Options o;
  for (int i = 1; i < argc; ++i) {
    const std::string arg = argv[i];
    if (arg == "--max-dt" && i + 1 < argc) {
      o.max_dt = std::stod(argv[++i]);
    } else if (o.estimate.empty()) {
      o.estimate = arg;
    } else if (o.reference.empty()) {
      o.reference = arg;
    } else {
      throw std::runtime_error("unexpected argument '" + arg + "'");
    }
  }
  if (o.reference.empty()) throw std::runtime_error("needs ESTIMATE_TUM and REFERENCE_TUM");
  return o;
}

int run(const Options& o) {
  const tacs::AteResult ate =
      tacs::computeAte(tacs::readTum(o.estimate), tacs::readTum(o.reference), o.max_dt);
  std::cout << "ATE " << ate.rmse << " m (mean " << ate.mean << ", max " << ate.max << ", "
            << ate.pairs << " poses)\n";
  return 0;
}

}  // namespace

int main(int argc, char** argv) {
  if (argc > 1 && (std::string(argv[1]) == "--help" || std::string(argv[1]) == "-h")) {
    printUsage();
    return 0;
  }
  return tacs::tools::toolMain("tacs_ate", argc, argv, parse, run, printUsage);
}
