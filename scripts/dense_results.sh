#!/usr/bin/env bash
# Dense LiDAR cost (issue "real sensors"): the legged office world seen by an OS0-128 (128 rings,
# 1024 columns, +-45 deg, motion distortion on, Ouster `t` times), run offline with the default
# configuration, seeds 1-3: from a bag tacs_sim wrote beforehand (what a user's recording costs)
# and simulated in-process (--world, the renderer then shares the cores). Prints a table of
# odometry cost per scan, pipeline rate and keyframe ATE; writes results/dense.md.
#
#   bash scripts/dense_results.sh [OUT_FILE]
#
# About 4 minutes on 2 cores; needs a built workspace and 2.5 GB of free space in $TMPDIR for one
# seed's bag at a time.
set -euo pipefail
REPO="$(cd "$(dirname "${BASH_SOURCE[0]}")/.." && pwd -P)"
source "$REPO/scripts/env.sh"
tacs_source_ws
OUT="${1:-$REPO/results/dense.md}"
WORK="$(mktemp -d)"
trap 'rm -rf "$WORK"' EXIT
/usr/bin/python3 - "$REPO/worlds/legged_office.json" "$WORK/os0_128.json" <<'PY'
import json, sys
world = json.load(open(sys.argv[1]))
world["sensor"] = {k: v for k, v in world["sensor"].items()
                   if k not in ("rings", "vfov_deg", "hres_deg", "columns")}
world["sensor"]["model"] = "os0_128"
json.dump(world, open(sys.argv[2], "w"))
PY
# A run's odometry mean and max ms and its scans/s.
cells() {
  /usr/bin/python3 - "$1/timing.json" <<'PY'
import json, sys
t = json.load(open(sys.argv[1]))
o = t["stages_ms"]["odometry"]
print(f"{o['mean_ms']:.1f} | {o['max_ms']:.1f} | {t['scans_per_s']:.1f}")
PY
}
rows=()
for seed in 1 2 3; do
  sim="$WORK/sim$seed"
  "$(tacs_bin tacs_sim)" "$WORK/os0_128.json" --out "$sim" --seed "$seed" >/dev/null 2>&1
  "$(tacs_bin tacs_offline)" --bag "$sim/sequence.bag" --topic /velodyne_points \
    --out "$WORK/bag$seed" --quiet >/dev/null
  rm -rf "$sim"
  "$(tacs_bin tacs_offline)" --world "$WORK/os0_128.json" --seed "$seed" --out "$WORK/world$seed" \
    --quiet >/dev/null
  ate="$("$(tacs_bin tacs_ate)" "$WORK/bag$seed/trajectory_tum.txt" \
    "$WORK/bag$seed/ground_truth_tum.txt" | awk '{printf "%.4f", $2}')"
  scans="$(/usr/bin/python3 -c "import json,sys; print(json.load(open(sys.argv[1]))['scans'])" \
    "$WORK/bag$seed/timing.json")"
  rows+=("| $seed | $scans | $(cells "$WORK/bag$seed") | $ate | $(cells "$WORK/world$seed") |")
  echo "${rows[-1]}" >&2
done
{
  echo "# Dense LiDAR: an OS0-128 world"
  echo
  echo "legged_office (1.5 m/s, 90 deg/s turns, gait vibration) seen by an OS0-128 (128 x 1024,"
  echo "131k beams per sweep, motion distortion on), default configuration, 2 cores: from a bag"
  echo "\`tacs_sim\` wrote beforehand, and simulated in-process (\`--world\`: the renderer shares the"
  echo "cores). Odometry ms: a scan's whole cost, its preparation (voxel grid, covariances) on the"
  echo "thread that reads the source and its registration on a thread of its own, each timed on"
  echo "cores shared with the keyframe stages (and the renderer). Keyframe ATE of the bag's run."
  echo "Made at $(git -C "$REPO" rev-parse --short HEAD); regenerate with \`bash scripts/dense_results.sh\`."
  echo
  echo "| seed | scans | bag: odometry mean ms | max ms | scans/s | keyframe ATE m | --world: odometry mean ms | max ms | scans/s |"
  echo "|---|---|---|---|---|---|---|---|---|"
  printf '%s\n' "${rows[@]}"
} >"$OUT"
echo "wrote $OUT" >&2
