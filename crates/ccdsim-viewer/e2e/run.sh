#!/usr/bin/env bash
# End-to-end tests of the browser viewer in headless Chromium.
#
# Needs Debian's chromium (apt-get install -y chromium) and Node.js with npm. Builds the
# `ccdsim` binary (which also records examples/shelves.json, balls resting on segments, and
# a scene pivots.test.mjs writes, balls rolling over shelves' ends) and
# the viewer's `slot_run`, `wall_run` and `rest_run` examples (which write a run that adds
# and removes bodies, one with moving walls and one where balls rest on planes), installs
# playwright-core from
# package-lock.json, then runs node's test runner; screenshots land in e2e/out/.
# `run.sh --which-bin` prints the binary's path and exits.
set -euo pipefail
here="$(cd "$(dirname "$0")" && pwd)"
root="$(cd "$here/../../.." && pwd)"
cd "$root"
# Ask cargo where it puts the binary: CARGO_TARGET_DIR or a config may move the target
# directory away from ./target.
bin="$("$root/scripts/target-dir")/debug/ccdsim"
if [ "${1:-}" = "--which-bin" ]; then
  echo "$bin"
  exit 0
fi
# The test profile (the dev profile: optimised, with debug assertions; see Cargo.toml) and
# the workspace's feature set: after `cargo test --workspace --tests`, as in
# scripts/test, the binary is the one that command already built, and only the examples
# compile here.
cargo build --locked --profile test --workspace --bin ccdsim \
  --example slot_run --example wall_run --example rest_run
slot_run="$(dirname "$bin")/examples/slot_run"
wall_run="$(dirname "$bin")/examples/wall_run"
rest_run="$(dirname "$bin")/examples/rest_run"
[ -x "$bin" ] || { echo "e2e: no ccdsim binary at $bin" >&2; exit 1; }
[ -x "$slot_run" ] || { echo "e2e: no slot_run example at $slot_run" >&2; exit 1; }
[ -x "$wall_run" ] || { echo "e2e: no wall_run example at $wall_run" >&2; exit 1; }
[ -x "$rest_run" ] || { echo "e2e: no rest_run example at $rest_run" >&2; exit 1; }
cd "$here"
npm ci --no-audit --no-fund
CCDSIM_BIN="$bin" SLOT_RUN_BIN="$slot_run" WALL_RUN_BIN="$wall_run" REST_RUN_BIN="$rest_run" \
  node --test viewer.test.mjs viewer3d.test.mjs slots.test.mjs sensors.test.mjs walls.test.mjs \
  resting.test.mjs pivots.test.mjs pool.test.mjs
