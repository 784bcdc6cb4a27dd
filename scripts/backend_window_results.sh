#!/usr/bin/env bash
# The backend's window solves (backend.window_keyframes) against a full solve per keyframe:
# bench_backend keyframe by keyframe on synthetic graphs of 1000 and 3000 keyframes, and
# tacs_eval on every world with config/eval/backend_window.yaml. Writes results/backend_window.md.
#
#   bash scripts/backend_window_results.sh [TRIALS] [OUT_FILE]
#
# About 40 minutes with 5 trials on 2 cores. Needs a built workspace.
set -euo pipefail
REPO="$(cd "$(dirname "${BASH_SOURCE[0]}")/.." && pwd -P)"
source "$REPO/scripts/env.sh"
tacs_source_ws
TRIALS="${1:-5}"
OUT="${2:-$REPO/results/backend_window.md}"
make -C "$TACS_WS/build" -j"$(nproc)" bench_backend >/dev/null  # not in the default target
WORK="$(mktemp -d)"
trap 'rm -rf "$WORK"' EXIT
bench=()
for keyframes in 1000 3000; do
  for window in 0 30; do
    bench+=("$("$(tacs_bin bench_backend)" --keyframes "$keyframes" --incremental 1 \
      --window "$window" | tail -1)")
  done
done
OMP_NUM_THREADS=1 "$(tacs_bin tacs_eval)" --methods "$REPO/config/eval/backend_window.yaml" \
  --trials "$TRIALS" --jobs "$(nproc)" --out "$WORK/eval" >/dev/null
{
  echo "# Backend: window solves against a full solve per keyframe"
  echo
  echo "\`backend.window_keyframes: K\` (docs/DESIGN.md, \"A keyframe's way\"): between full solves only"
  echo "the newest K keyframes and the walls no older keyframe saw move; 30 by default, 0 solves in"
  echo "full every time. Regenerate with \`bash scripts/backend_window_results.sh 5\`."
  echo
  echo "## Synthetic graphs, keyframe by keyframe (bench_backend --incremental 1)"
  echo
  echo "A 60 x 60 m lawn-mower path, a keyframe per metre, 300 walls, 8 wall observations per"
  echo "keyframe, a loop every 200 keyframes; optimised after every keyframe on the backend's"
  echo "schedule, then once more in full. One core."
  echo
  echo "| keyframes | window | full solves | mean ms per keyframe | mean ms, last 500 | max ms | t_FGO (s) | RMSE after the final full solve (m) |"
  echo "|---|---|---|---|---|---|---|---|"
  printf '%s\n' "${bench[@]}"
  echo
  echo "## The worlds (tacs_eval, $TRIALS trials, seeds 1-$TRIALS)"
  echo
  sed -n '/^## /,$p' "$WORK/eval/tables.md" | sed '/^## Figures/,$d'
} >"$OUT"
