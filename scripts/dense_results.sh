#!/usr/bin/env bash
# Dense LiDAR cost (issue "real sensors"): the legged office world seen by an OS0-128 (128 rings,
# 1024 columns, +-45 deg, motion distortion on, Ouster `t` times), run offline with the default
# configuration, seeds 1-3. Prints a table of odometry time per scan, pipeline rate and keyframe
# ATE; writes results/dense.md.
#
#   bash scripts/dense_results.sh [OUT_FILE]
#
# About 2 minutes on 2 cores. Needs a built workspace.
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
rows=()
for seed in 1 2 3; do
  run="$WORK/run$seed"
  "$(tacs_bin tacs_offline)" --world "$WORK/os0_128.json" --seed "$seed" --out "$run" --quiet >/dev/null
  ate="$("$(tacs_bin tacs_ate)" "$run/trajectory_tum.txt" "$run/ground_truth_tum.txt" | awk '{print $2}')"
  rows+=("$(/usr/bin/python3 - "$run/timing.json" "$seed" "$ate" <<'PY'
import json, sys
t = json.load(open(sys.argv[1]))
o = t["stages_ms"]["odometry"]
print(f"| {sys.argv[2]} | {t['scans']} | {o['mean_ms']:.1f} | {o['max_ms']:.1f} | "
      f"{t['scans_per_s']:.1f} | {float(sys.argv[3]):.4f} |")
PY
)")
  echo "${rows[-1]}" >&2
done
{
  echo "# Dense LiDAR: an OS0-128 world"
  echo
  echo "legged_office (1.5 m/s, 90 deg/s turns, gait vibration) seen by an OS0-128 (128 x 1024,"
  echo "131k beams per sweep, motion distortion on), default configuration, 2 cores."
  echo "Regenerate with \`bash scripts/dense_results.sh\`."
  echo
  echo "| seed | scans | odometry mean ms | odometry max ms | pipeline scans/s | keyframe ATE m |"
  echo "|---|---|---|---|---|---|"
  printf '%s\n' "${rows[@]}"
} >"$OUT"
echo "wrote $OUT" >&2
