// What every executable of the package (nodes, tools, benchmarks) does first in main(): the
// OpenMP wait policy and the heap set for a pipeline that shares two cores with other work.
#pragma once

#include <string>

namespace tacs {

/// libgomp spins at every barrier by default. The odometry opens dozens of short parallel loops
/// per scan, and the nodes (or the simulator's own thread team in tacs_offline) share the cores:
/// spinning threads then take the cores from the threads with work, and two threads run several
/// times slower than one. The policy is read once when libgomp loads, so the process re-executes
/// itself with OMP_WAIT_POLICY=passive unless the caller chose a policy (or the re-execution
/// fails: then it goes on with the default). Call before anything else in main(), before
/// ros::init (which removes the remapping arguments from argv). `executable` is what is re-executed
/// with argv; tests give another program.
void usePassiveOpenMpWait(char** argv, const char* executable = "/proc/self/exe");

/// The OpenMP wait policy in effect, for the benchmarks' headers.
std::string openMpWaitPolicy();

/// usePassiveOpenMpWait(argv), then retainFreedHeapMemory() (common/heap.h).
void setUpProcess(char** argv);

}  // namespace tacs
