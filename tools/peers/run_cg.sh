#!/usr/bin/env bash
# Times Pinocchio's analytical derivatives, computeMinverse and the code CppADCodeGen generates
# for six of its algorithms on a URDF (bench_cg.cpp). `rne bench --pinocchio` runs it beside
# run.sh unless told not to (--no-codegen).
#
#   bash tools/peers/run_cg.sh ROBOT.urdf [calls] [--reps R] [--flags "-O3 -march=native"]
#                              [--jacobian] [--keep DIR]      (run setup.sh --codegen first)
#
# Output: lines `name value` (see bench_cg.cpp); stderr has every repetition.
set -euo pipefail
source "$(cd "$(dirname "$0")" && pwd)/common.sh"
[ $# -ge 1 ] || { echo "usage: $0 ROBOT.urdf [calls] [bench_cg options]" >&2; exit 2; }
peers_require
[ -x "$peers_dir/bench_cg" ] || { echo "no bench_cg in $peers_dir: run bash $peers_here/setup.sh --codegen first" >&2; exit 2; }
urdf=$1; shift
calls=200000
if [ $# -gt 0 ] && [[ "$1" != --* ]]; then calls=$1; shift; fi
model=$(mktemp); gcc=$(mktemp)
trap 'rm -f "$model" "$gcc"' EXIT
# The generated C code is compiled at low priority; the timings themselves are not niced.
printf '#!/bin/sh\nexec nice /usr/bin/gcc "$@"\n' > "$gcc"; chmod +x "$gcc"
peers_dump "$urdf" "$model"
"$peers_dir/bench_cg" "$model" "$calls" --gcc "$gcc" "$@"
