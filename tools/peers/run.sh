#!/usr/bin/env bash
# Times plain Pinocchio on a URDF: RNEA, CRBA, ABA, nonLinearEffects and the generalized
# gravity, ns per call (bench.cpp). What `rne bench --pinocchio` runs.
#
#   bash tools/peers/run.sh ROBOT.urdf [calls]     (calls default 200000; run setup.sh first)
#
# Output: lines `name value` — nv, rnea_ns, crba_ns, aba_ns, nle_ns, gravity_ns.
set -euo pipefail
source "$(cd "$(dirname "$0")" && pwd)/common.sh"
[ $# -ge 1 ] || { echo "usage: $0 ROBOT.urdf [calls]" >&2; exit 2; }
peers_require
peers_build bench
model=$(mktemp)
trap 'rm -f "$model"' EXIT
peers_dump "$1" "$model"
"$peers_dir/bench" "$model" "${2:-200000}"
