#!/usr/bin/env bash
# Installs the Debian packages tacs_graphs needs (only what is missing) and builds the package in
# a catkin workspace outside the source tree. Prints the workspace path's setup file at the end.
#
#   bash scripts/setup.sh            install + build
#   TACS_WS=/path/ws bash ...        choose the workspace (default: ~/.cache/tacs_graphs/ws-<hash>)
#   TACS_SKIP_APT=1 bash ...         never call apt-get (offline machines)
set -euo pipefail

REPO="$(cd "$(dirname "${BASH_SOURCE[0]}")/.." && pwd -P)"
# shellcheck source=scripts/env.sh
source "$REPO/scripts/env.sh"

PACKAGES=(
  build-essential cmake python3-catkin-pkg
  ros-core-dev python3-rostest python3-rosbag python3-sensor-msgs rosbash python3-std-srvs
  libtf2-ros-dev libtf2-eigen-dev libpcl-conversions-dev
  libpcl-dev libceres-dev liboctomap-dev nlohmann-json3-dev libyaml-cpp-dev libpng-dev
  googletest libgtest-dev
)

install_packages() {
  local missing=()
  for p in "${PACKAGES[@]}"; do
    if ! dpkg-query -W -f='${Status}' "$p" 2>/dev/null | grep -q "install ok installed"; then
      missing+=("$p")
    fi
  done
  if [ ${#missing[@]} -eq 0 ]; then
    echo "[setup] all ${#PACKAGES[@]} Debian packages present"
    return
  fi
  if [ "${TACS_SKIP_APT:-0}" = 1 ]; then
    echo "[setup] missing packages and TACS_SKIP_APT=1: ${missing[*]}" >&2
    exit 1
  fi
  local sudo=""
  [ "$(id -u)" -eq 0 ] || sudo="sudo"
  echo "[setup] installing ${#missing[@]} Debian packages: ${missing[*]}"
  export DEBIAN_FRONTEND=noninteractive
  $sudo apt-get update -qq
  $sudo apt-get install -y -qq --no-install-recommends "${missing[@]}" >/dev/null
}

build() {
  mkdir -p "$TACS_WS/src"
  ln -sfn "$REPO" "$TACS_WS/src/tacs_graphs"
  cd "$TACS_WS"
  echo "[setup] building in $TACS_WS"
  catkin_make -j"$(nproc)" -DPYTHON_EXECUTABLE=/usr/bin/python3 -DPython3_EXECUTABLE=/usr/bin/python3 \
    -DCMAKE_BUILD_TYPE=Release \
    -DCATKIN_ENABLE_TESTING=ON "$@"
}

install_packages
build "$@"
echo "[setup] done: source $TACS_WS/devel/setup.bash"
