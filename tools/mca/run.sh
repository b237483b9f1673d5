#!/bin/bash
# What bounds a kernel's throughput, without timing it: this directory's crate is compiled
# to assembly for the machine (`-C target-cpu=native`, as the native `rne bench` build), each
# kernel's function body is cut out and llvm-mca, LLVM's model of the processor's pipelines,
# runs it as a loop. Per kernel (`lib.rs`): instructions, how many of them read or write the
# stack (spills and reloads), how many load a constant into every lane (`vbroadcastsd`), how
# many take one as an AVX-512 embedded broadcast (`{1toN}`), llvm-mca's block reciprocal
# throughput (the fewest cycles per call the pipelines allow if nothing waited on anything)
# and the busiest pipeline's
# cycles per call with its name (Zen 3: FPP0/FPP1 multiply and fused multiply-add,
# FPP2/FPP3 add, FPP45 the floating-point loads and stores). Issue 15 asks what bounds a
# kernel where rne is not 3x Pinocchio's generated code; docs/performance.md has the figures.
#
#   bash tools/mca/run.sh [CPU]      # from anywhere; CPU for llvm-mca, default znver3
set -euo pipefail
here=$(cd "$(dirname "$0")" && pwd)
cpu=${1:-znver3}
if ! command -v llvm-mca > /dev/null; then
  echo "tools/mca/run.sh: llvm-mca not found on PATH (it comes with LLVM, e.g. the llvm package)" >&2
  exit 1
fi
export CARGO_TARGET_DIR="$here/../../target/mca"
(cd "$here" && RUSTFLAGS="-C target-cpu=native" cargo rustc --release --quiet -- --emit asm)
asm=$(ls -t "$CARGO_TARGET_DIR"/release/deps/rne_mca_check-*.s | head -1)
body=$(mktemp)
trap 'rm -f "$body"' EXIT
printf '%-20s %6s %6s %6s %8s %11s  %s\n' kernel instrs stack bcast embedded throughput "busiest pipeline"
for kernel in $(grep -o '^_ZN13rne_mca_check[0-9]*mca_[^:]*:' "$asm" | sed 's/:$//'); do
  # The mangled name's path segment after the crate's: its length, then `mca_<name>`.
  name=$(echo "$kernel" | awk '{
    rest = substr($0, index($0, "rne_mca_check") + length("rne_mca_check"))
    match(rest, /^[0-9]+/); n = substr(rest, 1, RLENGTH)
    print substr(rest, RLENGTH + 1 + length("mca_"), n - length("mca_"))
  }')
  # The function's instructions: from its label to the end of its frame description,
  # without labels and assembler directives.
  awk -v f="$kernel:" '$0 == f {on = 1; next} on && /\.cfi_endproc/ {exit}
    on && $1 !~ /^\./ && $1 !~ /:$/ && $1 !~ /^#/ && NF {print}' "$asm" > "$body"
  if ! report=$(llvm-mca -mcpu="$cpu" -iterations=100 "$body" 2>&1); then
    echo "tools/mca/run.sh: llvm-mca failed on $name (-mcpu=$cpu):" >&2
    echo "$report" | head -3 >&2
    exit 1
  fi
  throughput=$(echo "$report" | awk '/Block RThroughput/ {print $3}')
  busiest=$(echo "$report" | awk '
    /^Resources:/ {r = 1; next}
    r && /^\[/ {gsub(/[][]/, "", $1); name[$1] = $3; next}
    r && /^$/ && length(name) {r = 0}
    /Resource pressure per iteration/ {getline header; getline values; next}
    END {
      n = split(header, h); split(values, v)
      for (i = 1; i <= n; i++) { gsub(/[][]/, "", h[i]); if (v[i] + 0 > best) {best = v[i] + 0; which = name[h[i]]} }
      printf "%.0f %s", best, which
    }')
  printf '%-20s %6d %6d %6d %8d %11s  %s\n' "$name" "$(wc -l < "$body")" "$(grep -c 'rsp' "$body" || true)" \
    "$(grep -c 'vbroadcastsd' "$body" || true)" "$(grep -c '{1to' "$body" || true)" "$throughput" "$busiest"
done
