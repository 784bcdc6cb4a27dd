#!/usr/bin/env bash
# Installs, builds and runs the main job on the bundled default configuration.
set -euo pipefail
REPO="$(cd "$(dirname "${BASH_SOURCE[0]}")/.." && pwd -P)"
source "$REPO/scripts/env.sh"

bash "$REPO/scripts/setup.sh"
tacs_source_ws
echo "[demo] validating config/default.yaml"
"$(tacs_bin tacs_config)" --config "$REPO/config/default.yaml"
