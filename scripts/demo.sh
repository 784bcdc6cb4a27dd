#!/usr/bin/env bash
# Installs, builds and runs the main job on the bundled default: the whole pipeline on the
# simulated smoke world (worlds/smoke.json, two rooms and a corridor), with the default
# configuration. The run folder goes to $TACS_DEMO_OUT (default /tmp/tacs_demo); it holds the
# trajectory, scene_graph.json, map.pcd, map.bt and topdown.png, plus the ground truth.
#
#   bash scripts/demo.sh [WORLD.json]
set -euo pipefail
REPO="$(cd "$(dirname "${BASH_SOURCE[0]}")/.." && pwd -P)"
source "$REPO/scripts/env.sh"

WORLD="${1:-$REPO/worlds/smoke.json}"
OUT="${TACS_DEMO_OUT:-/tmp/tacs_demo}"

bash "$REPO/scripts/setup.sh"
tacs_source_ws
echo "[demo] running tacs_offline on $WORLD"
OMP_WAIT_POLICY=passive "$(tacs_bin tacs_offline)" --world "$WORLD" \
  --config "$REPO/config/default.yaml" --out "$OUT"
echo "[demo] run folder: $OUT (open $OUT/topdown.png)"
