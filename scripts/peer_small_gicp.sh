#!/usr/bin/env bash
# small_gicp's GICP side by side with ours on the real HDL-32E scan pair (README "Test data"), in
# one process: rebuilds bench_gicp with the headers of a small_gicp checkout outside this
# repository (header-only; nothing of it is copied), runs it, and writes results/gicp_speed.md.
#
#   bash scripts/peer_small_gicp.sh SMALL_GICP_SRC [REPS]
#
# SMALL_GICP_SRC: a clone of github.com/koide3/small_gicp. Needs a built workspace; the include
# path is taken out of it again on exit, so a later build does not depend on the checkout.
set -euo pipefail
REPO="$(cd "$(dirname "${BASH_SOURCE[0]}")/.." && pwd -P)"
source "$REPO/scripts/env.sh"
tacs_source_ws
SG="$(cd "${1:?SMALL_GICP_SRC}" && pwd -P)"
REPS="${2:-30}"
trap 'cmake "$TACS_WS/build" -DTACS_SMALL_GICP_INCLUDE_DIR= >/dev/null' EXIT
cmake "$TACS_WS/build" -DTACS_SMALL_GICP_INCLUDE_DIR="$SG/include" >/dev/null
make -C "$TACS_WS/build" -j"$(nproc)" bench_gicp >/dev/null
report="$("$(tacs_bin bench_gicp)" --reps "$REPS")"
echo "$report"
{
  echo "# GICP speed: ours and small_gicp on the real HDL-32E scan pair"
  echo
  echo "One process, the same voxelised inputs, k = 10 neighbours per covariance, 1 m gate, up to"
  echo "30 iterations, the same stopping rule; the KD-trees and covariances of both clouds are built"
  echo "in every alignment. small_gicp $(git -C "$SG" rev-parse --short HEAD 2>/dev/null || echo '?')"
  echo "(RegistrationPCL, GICP) is compiled into the same binary with the same flags (Release, -O3,"
  echo "no -march=native). The head-to-head rows run interleaved, round by round; compare"
  echo "minima (the mean carries the shared machine's load). Regenerate with"
  echo "\`bash scripts/peer_small_gicp.sh SMALL_GICP_SRC\`."
  echo
  echo '```'
  echo "$report"
  echo '```'
} >"$REPO/results/gicp_speed.md"
