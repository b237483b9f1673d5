# Sourced by the peer scripts: where the private environment is, its Python, the C++ headers
# it installed, and how the timing programs are built.
#
# The environment lives in $RNE_PEERS_DIR (default ~/.cache/rne-peers); setup.sh creates it.

peers_here=$(cd "$(dirname "${BASH_SOURCE[0]}")" && pwd)
peers_dir=${RNE_PEERS_DIR:-$HOME/.cache/rne-peers}
peers_python="$peers_dir/venv/bin/python"

# Fails with a message naming setup.sh when the environment is missing.
peers_require() {
  if [ ! -x "$peers_python" ]; then
    echo "no Pinocchio in $peers_dir: run bash $peers_here/setup.sh first" >&2
    exit 2
  fi
}

# The install prefix of the cmeel packages (Pinocchio's, Eigen's and Boost's headers).
peers_prefix() {
  local prefix
  prefix=$(ls -d "$peers_dir"/venv/lib/python3*/site-packages/cmeel.prefix 2>/dev/null | head -1)
  [ -n "$prefix" ] || { echo "no cmeel.prefix under $peers_dir/venv" >&2; exit 2; }
  echo "$prefix"
}

# The directory of example-robot-data's URDFs.
peers_robots() {
  echo "$(peers_prefix)/share/example-robot-data/robots"
}

# peers_build NAME [extra linker flags...]: compiles $peers_here/NAME.cpp into $peers_dir/NAME
# when the program is missing or older than its source or the shared header. Header-only
# Pinocchio, -O3 -march=native, at low priority (a few minutes, once).
peers_build() {
  local name=$1; shift
  local exe="$peers_dir/$name" src="$peers_here/$name.cpp" header="$peers_here/peer_model.hpp"
  if [ -x "$exe" ] && [ ! "$src" -nt "$exe" ] && [ ! "$header" -nt "$exe" ]; then
    return 0
  fi
  local prefix
  prefix=$(peers_prefix)
  echo "building $exe (a few minutes, once)..." >&2
  nice g++ -O3 -march=native -DNDEBUG -std=c++17 -w \
    -DBOOST_MPL_LIMIT_LIST_SIZE=30 -DBOOST_MPL_LIMIT_VECTOR_SIZE=30 \
    -DBOOST_MPL_CFG_NO_PREPROCESSED_HEADERS -DBOOST_FUSION_INVOKE_MAX_ARITY=12 \
    -I"$peers_here" -I"$prefix/include" -I"$prefix/include/eigen3" \
    "$src" -o "$exe.tmp" "$@"
  mv "$exe.tmp" "$exe"
}

# peers_dump ROBOT.urdf FILE: writes the text model of dump.py (or of $RNE_PIN_DUMP, which
# `rne bench` sets to the dump.py beside the run.sh it was given).
peers_dump() {
  "$peers_python" "${RNE_PIN_DUMP:-$peers_here/dump.py}" "$1" > "$2"
}
