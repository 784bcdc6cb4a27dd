#!/usr/bin/env bash
# End-to-end speed of the offline runner on every world (issue "speed"): each world, seed 1, run
# alone on the machine by tacs_offline twice, from a bag that tacs_sim wrote beforehand (what a
# user's recording costs) and simulated in-process (--world, the renderer shares the cores), with
# the default configuration. Prints a table of scans/s, times real time, odometry time per scan
# and the time map.bt takes after the last scan against the whole run's; writes
# results/throughput.md.
#
#   bash scripts/throughput_results.sh [OUT_FILE]
#
# About 25 minutes on 2 cores; needs a built workspace and about 2 GB of free space in $TMPDIR
# for one world's bag at a time.
set -euo pipefail
REPO="$(cd "$(dirname "${BASH_SOURCE[0]}")/.." && pwd -P)"
source "$REPO/scripts/env.sh"
tacs_source_ws
OUT="${1:-$REPO/results/throughput.md}"
WORK="$(mktemp -d)"
trap 'rm -rf "$WORK"' EXIT
worlds=("${TACS_WORLDS:-}")
if [[ -z "${worlds[0]}" ]]; then
  mapfile -t worlds < <(cd "$REPO/worlds" && ls *.json | sed 's/\.json$//' | grep -v '^smoke$')
else
  read -r -a worlds <<<"${TACS_WORLDS}"
fi

# One row from a run: scans/s, x real time, odometry mean ms, map.bt s and its share.
row_of() {
  /usr/bin/python3 - "$1/timing.json" "$2" <<'PY'
import json, re, sys
t = json.load(open(sys.argv[1]))
log = open(sys.argv[2]).read()
m = re.search(r"map\.bt ([0-9.]+) s", log)
bt = float(m.group(1)) if m else float("nan")
odo = t["stages_ms"]["odometry"]["mean_ms"]
wall = t["wall_time_s"]
print(f"{t['scans_per_s']:.1f} | {t['scans_per_s'] / 10.0:.1f} | {odo:.1f} | {bt:.1f} | "
      f"{100.0 * bt / (wall + bt):.1f} %")
PY
}

rows=()
for w in "${worlds[@]}"; do
  sim="$WORK/sim"
  rm -rf "$sim" "$WORK/bag_run" "$WORK/world_run"
  "$(tacs_bin tacs_sim)" "$REPO/worlds/$w.json" --out "$sim" --seed 1 >/dev/null 2>&1
  scans="$(wc -l <"$sim/ground_truth_tum.txt")"
  "$(tacs_bin tacs_offline)" --bag "$sim/sequence.bag" --topic /velodyne_points \
    --out "$WORK/bag_run" --quiet >"$WORK/bag.log" 2>&1
  rm -rf "$sim"
  "$(tacs_bin tacs_offline)" --world "$REPO/worlds/$w.json" --seed 1 \
    --out "$WORK/world_run" --quiet >"$WORK/world.log" 2>&1
  rows+=("| $w | $scans | $(row_of "$WORK/bag_run" "$WORK/bag.log") | $(row_of "$WORK/world_run" "$WORK/world.log" | cut -d'|' -f1,2) |")
  echo "${rows[-1]}" >&2
done

{
  echo "# Offline throughput on the worlds"
  echo
  echo "Each world, seed 1, default configuration, run alone on the 2 cores of the machine by"
  echo "\`tacs_offline\`: from a bag \`tacs_sim\` wrote beforehand (a recording's cost), and"
  echo "simulated in-process (\`--world\`, the renderer then shares the cores). The worlds' LiDAR"
  echo "is a VLP-16 at 10 Hz (legged_office an OS1-64, motion distortion on), so x real time is"
  echo "scans/s / 10. Odometry ms: mean cost per scan, its preparation (on the thread that reads"
  echo "the source) and its registration (on a thread of its own, ahead of the keyframe stages),"
  echo "on cores they share with the keyframe stages. map.bt: seconds after the last scan, and"
  echo "their share of the run plus that export. Made at $(git -C "$REPO" rev-parse --short HEAD)"
  echo "with \`bash scripts/throughput_results.sh\`."
  echo
  echo "| world | scans | bag: scans/s | x real time | odometry ms | map.bt s | map.bt share | --world: scans/s | x real time |"
  echo "|---|---|---|---|---|---|---|---|---|"
  printf '%s\n' "${rows[@]}"
} >"$OUT"
cat "$OUT"
