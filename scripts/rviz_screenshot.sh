#!/usr/bin/env bash
# Runs the simulated demo (launch/demo_sim.launch) with rviz on a virtual X server and saves a
# screenshot of the whole screen once the bag has played.
#
#   scripts/rviz_screenshot.sh [WORLD.json] [OUT.png] [EXTRA_SECONDS]
#   TACS_PRIOR=1 scripts/rviz_screenshot.sh [WORLD.json] [OUT.png] [EXTRA_SECONDS]
#
# With TACS_PRIOR=1 a first session of the world (tacs_offline, seed 1) is the prior map and the
# played session (seed 2) starts at the path's middle waypoint: the screenshot shows the prior's
# graph ("Prior map" display) with the re-observed rooms highlighted.
#
# Needs the Debian packages rviz, xvfb (Xvfb) and imagemagick (import), and a built workspace:
# TACS_WS (default ~/.cache/tacs_graphs/ws-*) is sourced as by scripts/setup.sh.
set -euo pipefail

REPO="$(cd "$(dirname "${BASH_SOURCE[0]}")/.." && pwd -P)"
WORLD="${1:-$REPO/worlds/smoke.json}"
OUT="${2:-$PWD/tacs_graphs_rviz.png}"
EXTRA="${3:-8}"
# shellcheck source=scripts/env.sh
source "$REPO/scripts/env.sh"
tacs_source_ws

for tool in Xvfb import rviz; do
  command -v "$tool" >/dev/null || { echo "missing $tool (Debian: xvfb, imagemagick, rviz)" >&2; exit 1; }
done

WORK="$(mktemp -d)"
PIDS=()
cleanup() {
  for pid in "${PIDS[@]}"; do kill -INT "$pid" 2>/dev/null || true; done
  for pid in "${PIDS[@]}"; do wait "$pid" 2>/dev/null || true; done
  rm -rf "$WORK"
}
trap cleanup EXIT

PRIOR_ARGS=()
SIM_ARGS=()
if [ "${TACS_PRIOR:-0}" = 1 ]; then
  "$(tacs_bin tacs_offline)" --world "$WORLD" --seed 1 --out "$WORK/prior" --quiet >"$WORK/prior.log" 2>&1
  MIDDLE="$(python3 -c "import json,sys; print(len(json.load(open(sys.argv[1]))['trajectory']['waypoints'])//2)" "$WORLD")"
  SIM_ARGS=(--seed 2 --start-waypoint "$MIDDLE")
  PRIOR_ARGS=(prior_map:="$WORK/prior")
fi
"$(tacs_bin tacs_sim)" "$WORLD" --out "$WORK/sim" "${SIM_ARGS[@]}" >"$WORK/sim.log"
DURATION="$(python3 - "$WORK/sim/ground_truth_tum.txt" <<'PY'
import sys
rows = [l.split() for l in open(sys.argv[1]) if l.strip() and not l.startswith('#')]
print(int(float(rows[-1][0]) - float(rows[0][0])) + 1)
PY
)"

DISPLAY_NUM=":$((90 + RANDOM % 9))"
Xvfb "$DISPLAY_NUM" -screen 0 1280x800x24 -nolisten tcp >"$WORK/xvfb.log" 2>&1 &
PIDS+=($!)
export DISPLAY="$DISPLAY_NUM" LIBGL_ALWAYS_SOFTWARE=1
export ROS_MASTER_URI="http://localhost:$((11400 + RANDOM % 500))"
export ROS_HOME="$WORK/ros_home"
sleep 1
roslaunch -p "${ROS_MASTER_URI##*:}" tacs_graphs demo_sim.launch bag:="$WORK/sim/sequence.bag" \
  rviz:=true output_dir:="$WORK/out" "${PRIOR_ARGS[@]}" >"$WORK/launch.log" 2>&1 &
PIDS=($! "${PIDS[@]}")
echo "playing $DURATION s of $(basename "$WORLD") ..."
sleep "$((DURATION + 3 + EXTRA))"
import -window root "$OUT"
cp "$WORK/launch.log" "${OUT%.png}.launch.log"
echo "screenshot: $OUT (the launch's log: ${OUT%.png}.launch.log)"
if [ "${TACS_PRIOR:-0}" = 1 ]; then
  # The backend logs to ROS_HOME, not to the launch's output.
  grep -rh -m1 "Localized in the prior map" "$WORK/launch.log" "$ROS_HOME/log" 2>/dev/null ||
    echo "not localized in the prior map"
fi
