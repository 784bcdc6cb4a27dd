# Sourced by the scripts: where the catkin workspace lives. The default depends on the clone's
# path, so two clones never share a build.
: "${REPO:?REPO must be set before sourcing env.sh}"
if [ -z "${TACS_WS:-}" ]; then
  TACS_WS="${XDG_CACHE_HOME:-$HOME/.cache}/tacs_graphs/ws-$(printf '%s' "$REPO" | md5sum | cut -c1-8)"
fi
export TACS_WS
# Sources the workspace once it is built (setup.bash reads unset variables: no `set -u` here).
tacs_source_ws() {
  set +u
  # shellcheck disable=SC1091
  source "$TACS_WS/devel/setup.bash"
  set -u
}
# Path of one of the package's executables in the workspace.
tacs_bin() { printf '%s/devel/lib/tacs_graphs/%s' "$TACS_WS" "$1"; }
# The real BALM hall (README "Test data"), looked for where common/data_paths.h looks; prints
# its folder, or fails with the hint.
tacs_balm_dir() {
  local dir
  for dir in ${TACS_SHARED_DATA_DIR:-} "$REPO/../shared/data" \
    "${XDG_CACHE_HOME:-$HOME/.cache}/tacs_graphs/data"; do
    if [ -f "$dir/balm_indoor_hall/balm_to_bag.py" ]; then
      printf '%s/balm_indoor_hall' "$dir"
      return 0
    fi
  done
  echo "error: no balm_indoor_hall (README: Test data; bash scripts/get_test_data.sh balm_indoor_hall)" >&2
  return 1
}
