#!/usr/bin/env bash
# Regenerates results/faults.md: the live suite under faults, on the real hall (BALM, 1 Hz,
# handheld.launch) and on a world (legged_office, 10 Hz): kill -9 of each stateful node (backend,
# room_segmentation, loop_closure) at three random times while play_bag plays the bag (roslaunch
# respawns it, it replays its journal and asks for what it missed), and Ctrl-C of the launch at
# three times, the last after the bag's end (the shutdown save within roslaunch's 15 s, run.json "complete", no file of an
# earlier run). Each result is compared with the uninterrupted run: keyframes, ATE of the saved
# trajectory_tum.txt against the reference (hall: the reference poses; world: ground truth).
#
#   bash scripts/fault_results.sh [OUT.md] [SEED]   (needs a built workspace; about 30 minutes)
# With TACS_FAULT_WORK=DIR the runs go to DIR, and a second call with the same DIR runs only the
# cases that did not finish.
set -euo pipefail
REPO="$(cd "$(dirname "${BASH_SOURCE[0]}")/.." && pwd -P)"
source "$REPO/scripts/env.sh"
tacs_source_ws
OUT="${1:-$REPO/results/faults.md}"
SEED="${2:-7}"
WORK="${TACS_FAULT_WORK:-$(mktemp -d)}"
mkdir -p "$WORK"
trap 'rosnode kill -a >/dev/null 2>&1 || true' EXIT
ATE="$(tacs_bin tacs_ate)"

# start NAME LAUNCH: the suite under roslaunch into $WORK/NAME; sets LAUNCH_PID.
start() {
  roslaunch tacs_graphs "$2" use_sim_time:=true rviz:=false output_dir:="$WORK/$1" \
    >"$WORK/$1.launch.log" 2>&1 &
  LAUNCH_PID=$!
  sleep 8
}

# finish NAME: waits for the backend to drain, saves, stops the launch.
finish() {
  sleep 10
  rosservice call /backend/save >/dev/null
  kill -INT "$LAUNCH_PID"
  wait "$LAUNCH_PID" || true
}

# kill_run NAME LAUNCH BAG NODE AT_S: kill -9 of NODE AT_S seconds into play_bag.
kill_run() {
  [ -f "$WORK/$1.done" ] && return  # TACS_FAULT_WORK given again: finished cases are kept
  rm -rf "$WORK/$1" "$WORK/$1.killed"
  start "$1" "$2"
  rosrun tacs_graphs play_bag "$3" >"$WORK/$1.play.log" 2>&1 &
  local player=$!
  if [ "$4" != none ]; then
    sleep "$5"
    pkill -9 -f "__name:=$4( |$)" && echo "$4 $5" >"$WORK/$1.killed"
  fi
  wait "$player" || true
  finish "$1"
  touch "$WORK/$1.done"
}

# sigint_run NAME LAUNCH BAG AT_S: Ctrl-C of the launch AT_S seconds into play_bag, no save
# before; the seconds until roslaunch has ended go to NAME.stop_s.
sigint_run() {
  [ -f "$WORK/$1.done" ] && return
  rm -rf "$WORK/$1"
  mkdir -p "$WORK/$1"
  cp -r "$WORK/$5/." "$WORK/$1/"  # an earlier run's products in the folder
  touch -d '2000-01-01' "$WORK/$1"/*
  date +%s >"$WORK/$1.t_launch"
  start "$1" "$2"
  rosrun tacs_graphs play_bag "$3" >"$WORK/$1.play.log" 2>&1 &
  local player=$! t0
  sleep "$4"
  t0=$(date +%s.%N)
  kill -INT "$LAUNCH_PID"
  wait "$LAUNCH_PID" || true
  echo "$(date +%s.%N) - $t0" | bc >"$WORK/$1.stop_s"
  kill -INT "$player" 2>/dev/null || true
  wait "$player" || true
  touch "$WORK/$1.done"
}

[ -f "$WORK/world/sequence.bag" ] ||
  "$(tacs_bin tacs_sim)" "$REPO/worlds/legged_office.json" --out "$WORK/world" >/dev/null
[ -f "$WORK/hall.bag" ] || /usr/bin/python3 "$(tacs_balm_dir)/balm_to_bag.py" "$WORK/hall.bag" >/dev/null

# The kill times: three per node and data, drawn in the middle 80 % of the paced play.
times() { /usr/bin/python3 -c "import random; r = random.Random($SEED + $2); \
print(' '.join('%.1f' % r.uniform(0.1 * $1, 0.9 * $1) for _ in range(3)))"; }

for data in hall world; do
  if [ $data = hall ]; then launch=handheld.launch bag="$WORK/hall.bag"; else
    launch=tacs_graphs.launch bag="$WORK/world/sequence.bag"; fi
  kill_run "${data}_base" $launch "$bag" none 0
  play_s=$(grep -ao "played [0-9.]* s\|in [0-9.]* s" "$WORK/${data}_base.play.log" | head -1 | grep -o "[0-9.]*" || echo 20)
  k=0
  for node in backend room_segmentation loop_closure; do
    for t in $(times "$play_s" $k); do
      kill_run "${data}_kill_${node}_$t" $launch "$bag" $node "$t"
    done
    k=$((k + 1))
  done
  # Ctrl-C early, late, and after the bag (the whole map to save).
  for t in $(/usr/bin/python3 -c "print(' '.join('%.1f' % (f * $play_s) for f in (0.3, 0.7, 1.3)))"); do
    sigint_run "${data}_sigint_$t" $launch "$bag" "$t" "${data}_base"
  done
done

/usr/bin/python3 "$REPO/scripts/fault_table.py" "$WORK" "$ATE" "$(tacs_balm_dir)/poses_tum.txt" \
  "$WORK/world/ground_truth_tum.txt" "$OUT"
