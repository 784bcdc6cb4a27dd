#!/usr/bin/env bash
# Regenerates results/real/: the real BALM hall (README "Test data") run with the hand-held preset
# on our own odometry and on the reference poses (--poses), with figures and a table.
#
#   bash scripts/real_results.sh [OUT_DIR]      (default results/real; needs a built workspace)
set -euo pipefail
REPO="$(cd "$(dirname "${BASH_SOURCE[0]}")/.." && pwd -P)"
source "$REPO/scripts/env.sh"
tacs_source_ws
make -C "$TACS_WS/build" -j"$(nproc)" bench_real_odometry >/dev/null  # not in the default target
OUT="${1:-$REPO/results/real}"
DATA="$(tacs_balm_dir)"
WORK="$(mktemp -d)"
trap 'rm -rf "$WORK"' EXIT
/usr/bin/python3 "$DATA/balm_to_bag.py" "$WORK/hall.bag"
mkdir -p "$OUT"
for mode in odometry poses; do
  extra=()
  [ "$mode" = poses ] && extra=(--poses "$DATA/poses_tum.txt")
  "$(tacs_bin tacs_offline)" --bag "$WORK/hall.bag" --topic /os0_cloud_node/points \
    "${extra[@]}" --reference "$DATA/poses_tum.txt" --config "$REPO/config/handheld.yaml" \
    --out "$WORK/$mode" --quiet | tee "$WORK/$mode.log"
  cp "$WORK/$mode/topdown.png" "$OUT/topdown_$mode.png"
done
# The odometry alone on the cores (tacs_offline's 512 items per thread), then as in the nodes.
for items in 512 2048; do
  "$(tacs_bin bench_real_odometry)" --data "$(dirname "$DATA")" \
    --config "$REPO/config/handheld.yaml" --min-items-per-thread "$items" |
    tee "$WORK/bench_$items.log"
done
/usr/bin/python3 - "$WORK" "$OUT" <<'PY'
import json, re, sys
work, out = sys.argv[1], sys.argv[2]
rows = []
for mode, label in (("odometry", "our odometry (GICP)"), ("poses", "reference poses (--poses)")):
    g = json.load(open(f"{work}/{mode}/scene_graph.json"))
    t = json.load(open(f"{work}/{mode}/timing.json"))
    log = open(f"{work}/{mode}.log").read()
    ate = re.search(r"ATE ([0-9.]+) m \(keyframes", log).group(1)
    walls = sum(1 for w in g["walls"] if w.get("is_wall"))
    stages = t["stages_ms"]
    per = ", ".join(f"{k} {v['mean_ms']:.0f}" for k, v in sorted(stages.items()))
    rows.append(f"| {label} | {walls} | {len(g['rooms'])} | {ate} | "
                f"{t['odometry_recoveries']} | {t['scans_per_s']:.1f} | {per} |")
bench = []
for items, label in (("512", "alone on the cores (as tacs_offline)"),
                     ("2048", "as in the nodes (2048 items per thread)")):
    line = [l for l in open(f"{work}/bench_{items}.log") if l.startswith("| balm")][0]
    bench.append(line.replace("| balm_indoor_hall |", f"| balm_indoor_hall, {label} |", 1))
with open(f"{out}/table.md", "w") as f:
    f.write("| poses | walls | rooms | keyframe ATE m | recoveries | scans/s | mean ms per stage |\n")
    f.write("|---|---|---|---|---|---|---|\n")
    f.write("\n".join(rows) + "\n\n")
    f.write("Odometry alone (bench_real_odometry, config/handheld.yaml):\n\n")
    f.write("| data | scans | rejected | recoveries | ATE m | max m | path m | mean ms | median ms | max ms |\n")
    f.write("|---|---|---|---|---|---|---|---|---|---|\n")
    f.write("".join(bench))
print(open(f"{out}/table.md").read())
PY
