#!/usr/bin/env bash
# Fetches the real data sets that tests and benchmarks read from their public origins (GitHub
# repositories at pinned commits), checks every file against test/data_manifest/<set>.sha256 and
# installs each set that passes into the per-user data cache, where the tests find it (README
# "Test data"). A set that fails is not installed; the script goes on with the others and exits
# non-zero naming what it could not reach or verify.
#
#   bash scripts/get_test_data.sh [--dest DIR] [SET...]
#
#   SET        pcl_room_scans (1 MB), hdl32_scan_pair (2 MB), tiers_gt (5 MB), balm_indoor_hall
#              (downloads about 210 MB, keeps 104 MB); default: all four
#   --dest     install into DIR instead of ${XDG_CACHE_HOME:-~/.cache}/tacs_graphs/data
#   TACS_DATA_MIRROR=URL   fetch from a copy of the origins' <owner>/<repo>/<commit>/<path> layout
#              (default https://raw.githubusercontent.com; file:///path works too)
#
# Needs curl, sha256sum and, for balm_indoor_hall, python3 (standard library only).
#
# What it checks and what it cannot:
# - The checksums are those of the copies the tests were written against; every file of a set
#   must match them, so a moved, rewritten or truncated origin fails instead of changing the data.
# - pcl_room_scans, hdl32_scan_pair and tiers_gt are byte-for-byte copies of the origin files.
# - balm_indoor_hall is derived, not copied: the origin is 177 scans (429 MB) with fields x y z
#   intensity normal_x normal_y normal_z curvature. The script keeps every 2nd scan (indices 0, 2,
#   ..., 176), keeps x y z intensity (float32 values copied unchanged) and writes the poses of
#   alidarPose.csv in TUM format (reduce_balm below). The checksums show the result equals the
#   project's copy byte for byte; they cannot show that either is free of a reduction mistake.
# - Licences are the origins' own (README "Test data"); the script does not check them.
set -euo pipefail

REPO="$(cd "$(dirname "${BASH_SOURCE[0]}")/.." && pwd -P)"
MANIFESTS="$REPO/test/data_manifest"
MIRROR="${TACS_DATA_MIRROR:-https://raw.githubusercontent.com}"
DEST="${XDG_CACHE_HOME:-$HOME/.cache}/tacs_graphs/data"
ALL_SETS=(pcl_room_scans hdl32_scan_pair tiers_gt balm_indoor_hall)

# The origin of each set: "<owner>/<repo> <commit>".
origin() {
  case "$1" in
    pcl_room_scans) echo "PointCloudLibrary/data 5c26bdd0591ba150b91858b5c9fe5e91cb39ae86" ;;
    hdl32_scan_pair) echo "SMRT-AIST/fast_gicp b1b128f141f20ec3531ae23b08e9954c9b839401" ;;
    tiers_gt) echo "TIERS/tiers-lidars-dataset-enhanced 023e99ddec096a82b981f6d514c369cdec4de07b" ;;
    balm_indoor_hall) echo "hku-mars/BALM 5dc1bf927fcb65ef17f0e687f553c234d6b17365" ;;
  esac
}

# The files to download for each set: "<path in the repository> <name in the staging folder>".
files() {
  local i
  case "$1" in
    pcl_room_scans)
      for f in room_scan1.pcd room_scan2.pcd; do echo "tutorials/$f $f"; done ;;
    hdl32_scan_pair)
      for f in 251370668.pcd 251371071.pcd relative.txt; do echo "data/$f $f"; done ;;
    tiers_gt)
      for i in 06 07 08 09 10 11; do echo "data/ground_truth/GT_indoor$i.csv GT_indoor$i.csv"; done ;;
    balm_indoor_hall)
      echo "datas/benchmark_realworld/alidarPose.csv alidarPose.csv"
      for ((i = 0; i <= 176; i += 2)); do
        echo "datas/benchmark_realworld/full$i.pcd original/full$i.pcd"
      done ;;
  esac
}

# Writes scans/fullNNN.pcd (x y z intensity), scans.txt, poses_all_tum.txt and poses_tum.txt of
# balm_indoor_hall from original/full*.pcd and alidarPose.csv in folder $1, then removes original/.
reduce_balm() {
  python3 - "$1" <<'PY'
import math, os, shutil, sys

stage = sys.argv[1]

def reduce_pcd(src, dst):
    with open(src, "rb") as f:
        header = []
        while not header or not header[-1].startswith("DATA"):
            line = f.readline()
            if not line:
                sys.exit(f"{src}: no DATA line")
            header.append(line.decode("ascii").rstrip("\n"))
        body = f.read()
    h = dict(l.split(" ", 1) for l in header if not l.startswith("#"))
    fields = h["FIELDS"].split()
    if fields[:4] != ["x", "y", "z", "intensity"] or h["DATA"] != "binary" or \
            h["SIZE"].split() != ["4"] * len(fields) or h["TYPE"].split() != ["F"] * len(fields):
        sys.exit(f"{src}: not the expected binary float32 x y z intensity ... layout")
    step = 4 * len(fields)
    if len(body) != int(h["POINTS"]) * step:
        sys.exit(f"{src}: {len(body)} bytes of points, expected {int(h['POINTS']) * step}")
    kept = {"FIELDS": "x y z intensity", "SIZE": "4 4 4 4", "TYPE": "F F F F", "COUNT": "1 1 1 1"}
    out = [f"{l.split(' ', 1)[0]} {kept[l.split(' ', 1)[0]]}" if l.split(" ", 1)[0] in kept
           else l for l in header]
    with open(dst, "wb") as f:
        f.write(("\n".join(out) + "\n").encode("ascii"))
        f.write(b"".join(body[i:i + 16] for i in range(0, len(body), step)))

def quaternion(r):
    """x y z w of rotation matrix r (Shepperd's branches, normalised, sign as the branch gives)."""
    tr = r[0][0] + r[1][1] + r[2][2]
    if tr > 0:
        s = math.sqrt(tr + 1.0) * 2
        q = [(r[2][1] - r[1][2]) / s, (r[0][2] - r[2][0]) / s, (r[1][0] - r[0][1]) / s, 0.25 * s]
    elif r[0][0] > r[1][1] and r[0][0] > r[2][2]:
        s = math.sqrt(1.0 + r[0][0] - r[1][1] - r[2][2]) * 2
        q = [0.25 * s, (r[0][1] + r[1][0]) / s, (r[0][2] + r[2][0]) / s, (r[2][1] - r[1][2]) / s]
    elif r[1][1] > r[2][2]:
        s = math.sqrt(1.0 + r[1][1] - r[0][0] - r[2][2]) * 2
        q = [(r[0][1] + r[1][0]) / s, 0.25 * s, (r[1][2] + r[2][1]) / s, (r[0][2] - r[2][0]) / s]
    else:
        s = math.sqrt(1.0 + r[2][2] - r[0][0] - r[1][1]) * 2
        q = [(r[0][2] + r[2][0]) / s, (r[1][2] + r[2][1]) / s, 0.25 * s, (r[1][0] - r[0][1]) / s]
    n = math.sqrt(sum(v * v for v in q))
    return [v / n for v in q]

# alidarPose.csv: per scan 4 lines "r r r t," of [R t; 0 0 0 stamp], values kept as written.
rows = [l.strip().rstrip(",").split(",") for l in open(os.path.join(stage, "alidarPose.csv"))
        if l.strip()]
poses = []
for i in range(0, len(rows), 4):
    m = rows[i:i + 4]
    q = quaternion([[float(v) for v in row[:3]] for row in m[:3]])
    poses.append((m[3][3], f"{m[3][3]} {m[0][3]} {m[1][3]} {m[2][3]} " +
                  " ".join(f"{v:.9f}" for v in q)))
os.makedirs(os.path.join(stage, "scans"), exist_ok=True)
scans = ["# original_index timestamp file  (scans kept: every 2nd of the 177 in the source)"]
for index in range(0, len(poses), 2):
    name = f"scans/full{index:03d}.pcd"
    reduce_pcd(os.path.join(stage, "original", f"full{index}.pcd"), os.path.join(stage, name))
    scans.append(f"{index} {poses[index][0]} {name}")
for name, lines in [("scans.txt", scans), ("poses_all_tum.txt", [p[1] for p in poses]),
                    ("poses_tum.txt", [p[1] for p in poses[::2]])]:
    with open(os.path.join(stage, name), "w") as f:
        f.write("\n".join(lines) + "\n")
shutil.rmtree(os.path.join(stage, "original"))
PY
}

verify() {  # folder, set; prints the files that do not match
  (cd "$1" && sha256sum --quiet --strict -c "$MANIFESTS/$2.sha256" 2>/dev/null)
}

# Downloads, derives and verifies one set in a staging folder beside its final place, then moves
# it there, so the tests never see a half-fetched set.
fetch_set() {
  local set="$1" repo commit stage path name url rc
  read -r repo commit <<<"$(origin "$set")"
  stage="$DEST/.$set.partial"
  rm -rf "$stage" && mkdir -p "$stage" || return 1
  echo "[data] $set: fetching from $repo at ${commit:0:12}"
  while read -r path name; do
    url="$MIRROR/$repo/$commit/$path"
    mkdir -p "$(dirname "$stage/$name")"
    rc=0
    curl -fsSL --connect-timeout 20 --retry 2 -o "$stage/$name" "$url" 2>/dev/null || rc=$?
    if [ "$rc" -eq 22 ]; then
      echo "[data] $set: the origin has no $url (moved or removed?)" >&2
      return 1
    elif [ "$rc" -ne 0 ]; then
      echo "[data] $set: cannot reach $url (curl exit $rc: no network access?)" >&2
      return 1
    fi
  done < <(files "$set")
  if [ "$set" = balm_indoor_hall ]; then
    echo "[data] $set: keeping every 2nd scan, fields x y z intensity"
    reduce_balm "$stage" || { echo "[data] $set: reduction failed" >&2; return 1; }
  fi
  if ! verify "$stage" "$set" | sed "s/^/[data] $set: /" >&2; then  # pipefail: verify's status
    echo "[data] $set: checksums do not match test/data_manifest/$set.sha256; not installed" >&2
    return 1
  fi
  # Called as a condition, so set -e does not stop here on failure: each step is checked.
  if ! { cp "$MANIFESTS/$set.sha256" "$stage/SHA256SUMS" && rm -rf "${DEST:?}/$set" &&
    mv "$stage" "$DEST/$set"; }; then
    echo "[data] $set: cannot install into $DEST" >&2
    return 1
  fi
  echo "[data] $set: ok -> $DEST/$set"
}

sets=()
while [ $# -gt 0 ]; do
  case "$1" in
    --dest) DEST="$2"; shift 2 ;;
    -h | --help) sed -n '2,/^set -euo/p' "${BASH_SOURCE[0]}" | sed '$d; s/^# \{0,1\}//'; exit 0 ;;
    *)
      if [ -z "$(origin "$1")" ]; then
        echo "unknown data set '$1' (known: ${ALL_SETS[*]})" >&2
        exit 2
      fi
      sets+=("$1"); shift ;;
  esac
done
[ ${#sets[@]} -gt 0 ] || sets=("${ALL_SETS[@]}")
tools=(curl sha256sum)
[[ " ${sets[*]} " != *" balm_indoor_hall "* ]] || tools+=(python3)
for tool in "${tools[@]}"; do
  command -v "$tool" >/dev/null || { echo "[data] $tool is needed and not installed" >&2; exit 1; }
done
mkdir -p "$DEST"

failed=()
for set in "${sets[@]}"; do
  if [ -d "$DEST/$set" ] && verify "$DEST/$set" "$set" >/dev/null; then
    echo "[data] $set: ok (already in $DEST/$set)"
  elif ! fetch_set "$set"; then
    rm -rf "${DEST:?}/.$set.partial"
    failed+=("$set")
  fi
done
if [ -n "${TACS_SHARED_DATA_DIR:-}" ] && [ "$TACS_SHARED_DATA_DIR" != "$DEST" ]; then
  echo "[data] note: TACS_SHARED_DATA_DIR=$TACS_SHARED_DATA_DIR is set; the tests look only there"
fi
if [ ${#failed[@]} -gt 0 ]; then
  echo "[data] not fetched: ${failed[*]}" >&2
  exit 1
fi
echo "[data] done: ${sets[*]} in $DEST"
