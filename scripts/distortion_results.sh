#!/usr/bin/env bash
# Motion distortion on every world (issue "real sensors"): each world driven at 1.5 m/s with
# 90 deg/s turns, its sweeps rendered from one pose (no distortion) and from the pose at each
# firing's time (distortion, the sensor's per-point time field written), run with and without
# deskew. Keyframe ATE against the ground truth (tacs_ate, after SE(3) alignment). Then the same
# with the yaw rate ramped at 180 deg/s^2 (trajectory.max_yaw_accel_dps2) instead of stepped,
# undistorted and deskewed. Writes results/distortion.md.
#
#   bash scripts/distortion_results.sh [OUT_FILE]
#
# About 35 minutes on 2 cores. Needs a built workspace.
set -euo pipefail
REPO="$(cd "$(dirname "${BASH_SOURCE[0]}")/.." && pwd -P)"
source "$REPO/scripts/env.sh"
tacs_source_ws
OUT="${1:-$REPO/results/distortion.md}"
WORK="$(mktemp -d)"
trap 'rm -rf "$WORK"' EXIT
printf 'odometry:\n  deskew: false\n' >"$WORK/no_deskew.yaml"

# The world at 1.5 m/s and 90 deg/s, distortion on or off.
variant() {  # world.json distortion(true|false) out.json [yaw acceleration deg/s^2]
  /usr/bin/python3 - "$1" "$2" "$3" "${4:-0}" <<'PY'
import json, sys
world = json.load(open(sys.argv[1]))
world["trajectory"]["max_yaw_accel_dps2"] = float(sys.argv[4])
world["trajectory"]["speed_mps"] = 1.5
world["trajectory"]["max_yaw_rate_dps"] = 90.0
world["trajectory"]["max_accel_mps2"] = max(1.5, world["trajectory"].get("max_accel_mps2", 0.5))
world["sensor"]["motion_distortion"] = sys.argv[2] == "true"
json.dump(world, open(sys.argv[3], "w"))
PY
}

ate() {  # run folder -> keyframe ATE [m]
  "$(tacs_bin tacs_ate)" "$1/trajectory_tum.txt" "$1/ground_truth_tum.txt" | awk '{print $2}'
}

rows=()
for world in "$REPO"/worlds/*.json; do
  name="$(basename "$world" .json)"
  variant "$world" false "$WORK/$name.still.json"
  variant "$world" true "$WORK/$name.moving.json"
  "$(tacs_bin tacs_offline)" --world "$WORK/$name.still.json" --out "$WORK/$name.still" --quiet >/dev/null
  "$(tacs_bin tacs_offline)" --world "$WORK/$name.moving.json" --out "$WORK/$name.deskew" --quiet >/dev/null
  "$(tacs_bin tacs_offline)" --world "$WORK/$name.moving.json" --config "$WORK/no_deskew.yaml" \
    --out "$WORK/$name.raw" --quiet >/dev/null
  variant "$world" false "$WORK/$name.still_ramp.json" 180
  variant "$world" true "$WORK/$name.moving_ramp.json" 180
  "$(tacs_bin tacs_offline)" --world "$WORK/$name.still_ramp.json" --out "$WORK/$name.still_ramp" --quiet >/dev/null
  "$(tacs_bin tacs_offline)" --world "$WORK/$name.moving_ramp.json" --out "$WORK/$name.deskew_ramp" --quiet >/dev/null
  still_ramp="$(ate "$WORK/$name.still_ramp")"
  deskew_ramp="$(ate "$WORK/$name.deskew_ramp")"
  still="$(ate "$WORK/$name.still")"
  deskew="$(ate "$WORK/$name.deskew")"
  raw="$(ate "$WORK/$name.raw")"
  sensor="$(/usr/bin/python3 -c "import json,sys; print(json.load(open(sys.argv[1]))['sensor'].get('model','vlp16'))" "$world")"
  ratio="$(/usr/bin/python3 -c "import sys; print(f'{float(sys.argv[1]) / float(sys.argv[2]):.2f}')" "$deskew" "$still")"
  ratio_ramp="$(/usr/bin/python3 -c "import sys; print(f'{float(sys.argv[1]) / float(sys.argv[2]):.2f}')" "$deskew_ramp" "$still_ramp")"
  rows+=("| $name | $sensor | $(printf '%.4f' "$still") | $(printf '%.4f' "$raw") | $(printf '%.4f' "$deskew") | $ratio | $(printf '%.4f' "$still_ramp") | $(printf '%.4f' "$deskew_ramp") | $ratio_ramp |")
  echo "${rows[-1]}" >&2
done
{
  echo "# Motion distortion on the worlds"
  echo
  echo "Every world driven at 1.5 m/s with turns at up to 90 deg/s (\`trajectory.speed_mps\`,"
  echo "\`max_yaw_rate_dps\`), seed 1, default configuration. *Undistorted*: each sweep rendered from"
  echo "one pose. *Distorted*: each firing from the pose at its time, with the sensor's time field"
  echo "(VLP-16 \`time\`, Ouster \`t\`); run without deskew (\`odometry.deskew: false\`) and with it"
  echo "(the default). Keyframe ATE after SE(3) alignment (\`tacs_ate\`). Ratio: deskewed over"
  echo "undistorted. Worlds with gait vibration (\`jitter_deg\`) keep it in every column; a sweep"
  echo "from one pose freezes it, so only the distorted columns see the body move within a sweep."
  echo "*Ramped*: the same worlds with the yaw rate ramped up and down at 180 deg/s^2"
  echo "(\`trajectory.max_yaw_accel_dps2\`: 90 deg/s is reached in 0.5 s) instead of stepping to"
  echo "its limit between two firings, as the first four columns' paths do; no wheeled or legged"
  echo "robot steps its yaw rate, and a constant-velocity sweep cannot follow a step."
  echo "Made at $(git -C "$REPO" rev-parse --short HEAD); regenerate with"
  echo "\`bash scripts/distortion_results.sh\`."
  echo
  echo "| world | sensor | undistorted ATE m | distorted, no deskew | distorted, deskewed | ratio | ramped: undistorted | ramped: deskewed | ramped: ratio |"
  echo "|---|---|---|---|---|---|---|---|---|"
  printf '%s\n' "${rows[@]}"
} >"$OUT"
