#!/bin/bash
# Generation time and release compile time (first build of the crate, then after touching it)
# of the biggest robots of example-robot-data on a floating base: issue 11's "all kernels
# generate in under 1 s and the module compiles (release, incremental) in under 30 s on 2
# cores". Needs the environment of tools/peers/setup.sh (it installs
# example-robot-data) and a release build of rne (`cargo build --release -p rne-cli`).
#
#   bash tools/scale/measure.sh            # from the repository root
set -euo pipefail
root=$(cd "$(dirname "$0")/../.." && pwd)
robots=${ROBOTS_DIR:-$(bash "$root/tools/peers/robots.sh")}
rne="$root/target/release/rne"
crate="$root/tools/scale"
export CARGO_TARGET_DIR="$root/target/scale"
format="%e s wall, %U s user, %S s sys, %M KB max RSS"
uptime
for urdf in talos_data/robots/talos_full_v2.urdf g1_description/urdf/g1_29dof_with_hand_rev_1_0.urdf; do
  name=$(basename "$urdf")
  "$rne" stats --floating-base "$robots/$urdf" | tail -1 | sed "s|^|$name: |"
  cp "$robots/$urdf" "$crate/robot.urdf"
  (cd "$crate" && cargo build --release --quiet 2>/dev/null || true)   # dependencies
  (cd "$crate" && cargo clean --release -p rne-scale-check --quiet)
  (cd "$crate" && /usr/bin/time -f "$name first build: $format" cargo build --release --quiet)
  touch "$crate/src/lib.rs"
  (cd "$crate" && /usr/bin/time -f "$name incremental: $format" cargo build --release --quiet)
  uptime
done
rm -f "$crate/robot.urdf"
