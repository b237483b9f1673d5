#!/usr/bin/env bash
# Times Pinocchio's computeJointJacobians (alone and with every joint's Jacobian read out),
# J-dot q-dot (two ways) and computeJointTorqueRegressor on a URDF (bench_extra.cpp): the
# algorithms rne's kinematics and identification kernels are compared with. `rne bench
# --pinocchio` runs it beside run.sh.
#
#   bash tools/peers/run_extra.sh ROBOT.urdf [calls] [reps]   (run setup.sh first)
#
# Output: lines `name value` (see bench_extra.cpp), ns per call.
set -euo pipefail
source "$(cd "$(dirname "$0")" && pwd)/common.sh"
[ $# -ge 1 ] || { echo "usage: $0 ROBOT.urdf [calls] [reps]" >&2; exit 2; }
peers_require
peers_build bench_extra
model=$(mktemp)
trap 'rm -f "$model"' EXIT
peers_dump "$1" "$model"
"$peers_dir/bench_extra" "$model" "${2:-200000}" "${3:-5}"
