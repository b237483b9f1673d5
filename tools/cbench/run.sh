#!/bin/bash
# Time per call of rne's C kernels (`rne emit --lang c`) beside the Rust kernels they equal
# bit for bit: UR5 and the Panda with its hand (9 joints), inverse dynamics, M, forward
# dynamics and both derivatives. The C (`bench.c`) is built with `gcc -O2` and with
# `gcc -O3 -march=native`; the Rust (`src/main.rs`, the same states and loop) in a release
# build for baseline x86-64 and with `-C target-cpu=native`. Each figure is the fastest run's
# time per call (runs of 128 calls on consecutive states of 1024, repeated for a second), in
# nanoseconds.
#
#   bash tools/cbench/run.sh          # from anywhere; CC overrides gcc, RNE the rne binary
#                                     # (default: a release build, made first)
set -euo pipefail
root=$(cd "$(dirname "$0")/../.." && pwd)
here="$root/tools/cbench"
out="$root/target/cbench"
cc=${CC:-gcc}
outputs=inverse_dynamics,mass_matrix,forward_dynamics,inverse_dynamics_derivatives,forward_dynamics_derivatives
mkdir -p "$out"
rne=${RNE:-}
if [ -z "$rne" ]; then
  (cd "$root" && cargo build --release --quiet -p rne-cli --bin rne)
  rne="$root/target/release/rne"
fi
(cd "$here" && CARGO_TARGET_DIR="$out/rust" cargo build --release --quiet)
(cd "$here" && CARGO_TARGET_DIR="$out/rust-native" RUSTFLAGS="-C target-cpu=native" \
  cargo build --release --quiet)
"$cc" --version | head -1
rustc --version
for robot in ur5 panda; do
  "$rne" emit --lang c "$robot" --outputs "$outputs" --out "$out/c" > /dev/null
  upper=$(echo "$robot" | tr a-z A-Z)
  for flags in "-O2" "-O3 -march=native"; do
    exe="$out/bench-$robot${flags// /}"
    # shellcheck disable=SC2086
    "$cc" -std=c99 $flags -DROBOT="$robot" -DUPPER="$upper" -DROBOT_H="\"$robot.h\"" \
      -I "$out/c" "$here/bench.c" "$out/c/$robot.c" -lm -o "$exe"
  done
  echo
  echo "$robot: ns per call"
  printf '%-30s %10s %10s %20s %12s\n' kernel "C -O2" "Rust" "C -O3 -march=native" "Rust native"
  paste <("$out/bench-$robot-O2") <("$out/rust/release/rne-cbench" "$robot") \
        <("$out/bench-$robot-O3-march=native") <("$out/rust-native/release/rne-cbench" "$robot") |
    awk '{printf "%-30s %10s %10s %20s %12s\n", $1, $2, $5, $8, $11}'
done
