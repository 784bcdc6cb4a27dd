#!/usr/bin/env bash
# Installs, builds and runs every test: core gtests (no ROS master), ROS-layer gtests and the
# rostest integration tests. Exits non-zero on any failure; ends with a summary line.
set -euo pipefail
REPO="$(cd "$(dirname "${BASH_SOURCE[0]}")/.." && pwd -P)"
source "$REPO/scripts/env.sh"

bash "$REPO/scripts/setup.sh"
tacs_source_ws
cd "$TACS_WS"
rm -rf build/test_results
catkin_make -j"$(nproc)" tests benchmarks >/dev/null
status=0
(cd build && ctest --output-on-failure) || status=$?
catkin_test_results build/test_results || status=$?
/usr/bin/python3 "$REPO/scripts/summarize_test_results.py" build/test_results || status=$?
exit $status
