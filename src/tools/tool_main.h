// The shared main() of the command-line tools: parse the command line (exit 2 with the usage on
// a bad one), run (exit 1 with the error on an exception), else the run's own exit status.
#pragma once

#include <exception>
#include <iostream>
#include <string>

#include "tacs_graphs/common/process_setup.h"

namespace tacs::tools {

template <class Parse, class Run, class Usage>
int toolMain(const std::string& name, int argc, char** argv, Parse parse, Run run, Usage usage) {
  setUpProcess(argv);
  decltype(parse(argc, argv)) options;
  try {
    options = parse(argc, argv);
  } catch (const std::exception& e) {
    std::cerr << name << ": " << e.what() << "\n";
    usage();
    return 2;
  }
  try {
    return run(options);
  } catch (const std::exception& e) {
    std::cerr << "\nerror: " << e.what() << "\n";
    return 1;
  }
}

}  // namespace tacs::tools
