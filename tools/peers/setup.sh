#!/usr/bin/env bash
# Installs the peers rne is compared with into a private environment, and builds the timing
# programs. Idempotent; about 5 minutes the first time.
#
#   bash tools/peers/setup.sh             Pinocchio 4.1.0 (C++ headers and Python bindings) and
#                                         example-robot-data from PyPI; builds bench and
#                                         bench_extra
#   bash tools/peers/setup.sh --codegen   also CppAD and CppADCodeGen, and builds bench_cg (the
#                                         code-generation timer: about 15 minutes and 8 GB of
#                                         memory to compile, once; needs /usr/bin/gcc at run time)
#
# The environment goes to $RNE_PEERS_DIR (default ~/.cache/rne-peers), never into the
# repository. Needs python3 with venv, g++ and network access to PyPI.
set -euo pipefail
source "$(cd "$(dirname "$0")" && pwd)/common.sh"
codegen=0
for arg in "$@"; do
  case "$arg" in
    --codegen) codegen=1 ;;
    *) echo "usage: $0 [--codegen]" >&2; exit 2 ;;
  esac
done
mkdir -p "$peers_dir"
if [ ! -x "$peers_python" ]; then
  python3 -m venv "$peers_dir/venv"
fi
"$peers_dir/venv/bin/pip" install -q "pin==4.1.0" cmeel-eigen example-robot-data "mujoco==3.3.7"
peers_build bench
peers_build bench_extra
if [ "$codegen" = 1 ]; then
  # The versions Pinocchio 4.1.0's pinocchio/codegen/cppadcg-algo.hpp builds with.
  "$peers_dir/venv/bin/pip" install -q "cmeel-cppad==20250000.2" "cmeel-cppadcodegen==2.4.3"
  [ -x /usr/bin/gcc ] || { echo "bench_cg needs /usr/bin/gcc to compile generated code" >&2; exit 2; }
  peers_build bench_cg -ldl
fi
echo "ready: $peers_dir" >&2
echo "example URDFs: $(peers_robots)" >&2
