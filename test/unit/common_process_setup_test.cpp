#include <gtest/gtest.h>
#include <sys/wait.h>
#include <unistd.h>

#include <cstdlib>
#include <string>

#include "tacs_graphs/common/process_setup.h"

namespace tacs {
namespace {

// The re-executed program is a shell that exits 0 only when it sees the passive policy.
TEST(UsePassiveOpenMpWait, TheProcessIsRunAgainWithThePassivePolicy) {
  const pid_t pid = fork();
  ASSERT_GE(pid, 0);
  if (pid == 0) {
    unsetenv("OMP_WAIT_POLICY");
    char name[] = "sh";
    char command_flag[] = "-c";
    char command[] = "test \"$OMP_WAIT_POLICY\" = passive || exit 3";
    char* args[] = {name, command_flag, command, nullptr};
    usePassiveOpenMpWait(args, "/bin/sh");
    _exit(4);  // not re-executed
  }
  int status = 0;
  ASSERT_EQ(waitpid(pid, &status, 0), pid);
  ASSERT_TRUE(WIFEXITED(status));
  EXPECT_EQ(WEXITSTATUS(status), 0) << "3: the child saw another policy; 4: it was not re-executed";
}

TEST(UsePassiveOpenMpWait, APolicyTheCallerChoseIsKept) {
  const char* before = std::getenv("OMP_WAIT_POLICY");
  const std::string saved = before ? before : "";
  setenv("OMP_WAIT_POLICY", "active", 1);
  char name[] = "sh";
  char command_flag[] = "-c";
  char command[] = "exit 5";
  char* args[] = {name, command_flag, command, nullptr};
  usePassiveOpenMpWait(args, "/bin/sh");  // returns: no re-execution
  EXPECT_EQ(openMpWaitPolicy(), "active");
  if (before) {
    setenv("OMP_WAIT_POLICY", saved.c_str(), 1);
  } else {
    unsetenv("OMP_WAIT_POLICY");
  }
}

}  // namespace
}  // namespace tacs
