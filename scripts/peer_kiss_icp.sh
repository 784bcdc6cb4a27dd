#!/usr/bin/env bash
# KISS-ICP side by side with our odometry on the real BALM hall (README "Test data"): builds
# KISS-ICP's C++ core from a checkout outside this repository, runs it on the 89 scans with the
# library's defaults (voxel 1.0 m and 0.5 m; no deskew, the scans carry no per-point time) and
# scores its poses with tacs_offline --poses ... --reference (the same ATE as ours). Writes
# results/real/kiss_icp.md.
#
#   bash scripts/peer_kiss_icp.sh KISS_ICP_SRC SOPHUS_SRC [OUT_DIR]
#
# KISS_ICP_SRC: a clone of github.com/PRBonn/kiss-icp; SOPHUS_SRC: one of github.com/strasdat/Sophus
# (header-only; no Debian package). Needs robin-map-dev and libtbb-dev, and a built workspace.
set -euo pipefail
REPO="$(cd "$(dirname "${BASH_SOURCE[0]}")/.." && pwd -P)"
source "$REPO/scripts/env.sh"
tacs_source_ws
make -C "$TACS_WS/build" -j"$(nproc)" bench_real_odometry >/dev/null  # not in the default target
KISS="$(cd "${1:?KISS_ICP_SRC}" && pwd -P)"
SOPHUS="$(cd "${2:?SOPHUS_SRC}" && pwd -P)"
OUT="${3:-$REPO/results/real}"
DATA="$(tacs_balm_dir)"
for pkg in robin-map-dev libtbb-dev; do
  dpkg -s "$pkg" >/dev/null 2>&1 || { echo "error: apt-get install $pkg" >&2; exit 1; }
done
WORK="$(mktemp -d)"
trap 'rm -rf "$WORK"' EXIT
cmake -S "$SOPHUS" -B "$WORK/sophus" -DCMAKE_INSTALL_PREFIX="$WORK/prefix" \
  -DBUILD_SOPHUS_TESTS=OFF -DBUILD_SOPHUS_EXAMPLES=OFF -DSOPHUS_USE_BASIC_LOGGING=ON >/dev/null
cmake --build "$WORK/sophus" --target install >/dev/null
cmake -S "$KISS/cpp/kiss_icp" -B "$WORK/kiss" -DCMAKE_PREFIX_PATH="$WORK/prefix" \
  -DUSE_CCACHE=OFF >/dev/null
cmake --build "$WORK/kiss" -j2 >/dev/null
g++ -O2 -std=c++17 -DSOPHUS_USE_BASIC_LOGGING "$REPO/bench/peers/kiss_icp_balm.cpp" \
  -I"$KISS/cpp" -I"$WORK/prefix/include" -I/usr/include/eigen3 -I/usr/include/pcl-1.13 \
  "$WORK/kiss/pipeline/libkiss_icp_pipeline.a" "$WORK/kiss/core/libkiss_icp_core.a" \
  -ltbb -lpcl_io -lpcl_common -o "$WORK/kiss_icp_balm"
/usr/bin/python3 "$DATA/balm_to_bag.py" "$WORK/hall.bag" >/dev/null
rows=()
for voxel in 1.0 0.5; do
  timing="$("$WORK/kiss_icp_balm" "$DATA" "$voxel" "$WORK/kiss_$voxel.txt" 2>&1)"
  ate="$("$(tacs_bin tacs_offline)" --bag "$WORK/hall.bag" --topic /os0_cloud_node/points \
    --poses "$WORK/kiss_$voxel.txt" --poses-frame sensor --reference "$DATA/poses_tum.txt" \
    --config "$REPO/config/handheld.yaml" --out "$WORK/run_$voxel" --quiet 2>/dev/null |
    sed -n 's/.*odometry ATE \([0-9.]*\) m.*/\1/p')"
  mean="$(echo "$timing" | sed -n 's/.*mean_ms \([0-9.]*\).*/\1/p')"
  max="$(echo "$timing" | sed -n 's/.*max_ms \([0-9.]*\).*/\1/p')"
  rows+=("| KISS-ICP $(git -C "$KISS" rev-parse --short HEAD 2>/dev/null || echo '?'), voxel $voxel m | $ate | $(printf '%.1f' "$mean") | $(printf '%.1f' "$max") |")
done
ours="$("$(tacs_bin bench_real_odometry)" --data "$(dirname "$DATA")" --config "$REPO/config/handheld.yaml" |
  awk -F'|' '/^\| balm/ {gsub(/ /,""); print "| ours (GICP, config/handheld.yaml) | " $6 " | " $9 " | " $11 " |"}')"
mkdir -p "$OUT"
{
  echo "# KISS-ICP and our odometry on the real hall"
  echo
  echo "89 hand-held scans at 1 Hz (README \"Test data\"), odometry only, 2 cores. ATE: positions after an"
  echo "SE(3) alignment to poses_tum.txt. Time: registration per scan (KISS-ICP's RegisterFrame; our"
  echo "LidarOdometry::process). Regenerate with \`bash scripts/peer_kiss_icp.sh KISS_ICP_SRC SOPHUS_SRC\`."
  echo
  echo "| odometry | ATE m | mean ms | max ms |"
  echo "|---|---|---|---|"
  echo "$ours"
  printf '%s\n' "${rows[@]}"
} > "$OUT/kiss_icp.md"
cat "$OUT/kiss_icp.md"
