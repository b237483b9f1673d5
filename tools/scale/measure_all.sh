#!/bin/bash
# Macro expansion time and release compile time of a module with every kernel (derivatives,
# Jacobians and regressors included: this directory's crate with the feature `every-kernel`)
# for the Panda arm with its fingers (fixed base) and Talos
# (floating): issue 15's "report macro expansion time and rustc time of the generated modules
# for Panda and a 30-joint humanoid (all kernels including derivatives)". The phases are
# rustc's own (`-Z time-passes`, on the stable compiler through RUSTC_BOOTSTRAP=1, a
# measurement only): `macro_expand_crate` is the macro's run (generation included), `total`
# the crate's compilation. Needs the environment of tools/peers/setup.sh for
# Talos (it installs example-robot-data).
#
#   bash tools/scale/measure_all.sh            # from the repository root
set -euo pipefail
root=$(cd "$(dirname "$0")/../.." && pwd)
robots=${ROBOTS_DIR:-$(bash "$root/tools/peers/robots.sh")}
crate="$root/tools/scale"
export CARGO_TARGET_DIR="$root/target/scale"
export RUSTC_BOOTSTRAP=1
uptime
measure() {
  local name=$1 urdf=$2 features=$3
  cp "$urdf" "$crate/robot.urdf"
  (cd "$crate" && cargo build --release --quiet $features 2>/dev/null || true)   # dependencies
  touch "$crate/src/lib.rs"
  (cd "$crate" && /usr/bin/time -f "cargo %e s wall, %U s user, %M KB max RSS" \
    cargo rustc --release --quiet $features -- -Z time-passes 2>&1 |
    grep -E "macro_expand_crate|\stotal$|cargo" | sed "s|^|$name: |")
  uptime
}
measure "panda (9 joints, fixed base)" "$root/rne-models/robots/panda.urdf" "--features every-kernel,fixed-base"
measure "talos_full_v2 (32 joints, floating)" "$robots/talos_data/robots/talos_full_v2.urdf" "--features every-kernel"
rm -f "$crate/robot.urdf"
