#!/usr/bin/env bash
# Times Pinocchio's computeJointJacobians (alone and with every joint's Jacobian read out),
# J-dot q-dot and computeJointTorqueRegressor on a URDF: bench_extra.cpp, built on first use
# (or when the source is newer) against the Pinocchio that ../shared/tools/pinocchio/setup.sh
# installs into $RNE_PIN_DIR (default ~/.cache/rne-pinocchio).
# Usage: run_extra.sh ROBOT.urdf [calls] [reps]
# Output: lines `name value` (see bench_extra.cpp); ns per call.
set -euo pipefail
here=$(cd "$(dirname "$0")" && pwd)
dir=${RNE_PIN_DIR:-$HOME/.cache/rne-pinocchio}
python="$dir/venv/bin/python"
[ -x "$python" ] || { echo "no Pinocchio in $dir: run ../shared/tools/pinocchio/setup.sh first" >&2; exit 2; }
# dump.py of the shared tools writes the text model; look beside this script's shared copy.
dump=${RNE_PIN_DUMP:-$here/../../../shared/tools/pinocchio/dump.py}
[ -f "$dump" ] || { echo "no dump.py at $dump: set RNE_PIN_DUMP to the shared tools' dump.py" >&2; exit 2; }
[ $# -ge 1 ] || { echo "usage: $0 ROBOT.urdf [calls] [reps]" >&2; exit 2; }
prefix=$(ls -d "$dir"/venv/lib/python3*/site-packages/cmeel.prefix | head -1)
exe="$dir/bench_extra"
if [ ! -x "$exe" ] || [ "$here/bench_extra.cpp" -nt "$exe" ]; then
  echo "building $exe (a few minutes, once)..." >&2
  nice g++ -O3 -march=native -DNDEBUG -std=c++17 -w \
    -DBOOST_MPL_LIMIT_LIST_SIZE=30 -DBOOST_MPL_LIMIT_VECTOR_SIZE=30 \
    -DBOOST_MPL_CFG_NO_PREPROCESSED_HEADERS -DBOOST_FUSION_INVOKE_MAX_ARITY=12 \
    -I"$prefix/include" -I"$prefix/include/eigen3" \
    "$here/bench_extra.cpp" -o "$exe.tmp"
  mv "$exe.tmp" "$exe"
fi
model=$(mktemp)
trap 'rm -f "$model"' EXIT
"$python" "$dump" "$1" > "$model"
"$exe" "$model" "${2:-200000}" "${3:-5}"
