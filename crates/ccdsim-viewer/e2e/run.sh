#!/usr/bin/env bash
# End-to-end tests of the browser viewer in headless Chromium.
#
# Needs Debian's chromium (apt-get install -y chromium) and Node.js with npm. Builds the
# `ccdsim` binary, installs playwright-core from package-lock.json, then runs node's test
# runner; screenshots land in e2e/out/.
set -euo pipefail
here="$(cd "$(dirname "$0")" && pwd)"
root="$(cd "$here/../../.." && pwd)"
cd "$root"
cargo build --locked -p ccdsim-cli
cd "$here"
npm ci --no-audit --no-fund
CCDSIM_BIN="$root/target/debug/ccdsim" node --test viewer.test.mjs viewer3d.test.mjs
