#include "tacs_graphs/common/process_setup.h"

#include <unistd.h>

#include <cstdlib>

#include "tacs_graphs/common/heap.h"

namespace tacs {

void usePassiveOpenMpWait(char** argv, const char* executable) {
  if (std::getenv("OMP_WAIT_POLICY")) return;
  setenv("OMP_WAIT_POLICY", "passive", 1);
  execv(executable, argv);  // returns only on failure: then run with the default policy
}

std::string openMpWaitPolicy() {
  const char* policy = std::getenv("OMP_WAIT_POLICY");
  return policy ? policy : "default (active spinning)";
}

void setUpProcess(char** argv) {
  usePassiveOpenMpWait(argv);
  retainFreedHeapMemory();
}

}  // namespace tacs
