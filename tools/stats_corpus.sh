#!/usr/bin/env bash
# `rne stats` (all 18 kernels) on every URDF under a directory, on the file's own base and on a
# floating base, as a markdown table: per robot and base, the kernels generated, the ones
# undefined (a joint that moves no mass) or the error, and the generation time. A panic, a
# backtrace or a timeout would show in the table as such.
#
#   bash tools/stats_corpus.sh DIR [RNE] > table.md
#
# RNE is the rne binary (default: target/release/rne; build it with
# `cargo build --release -p rne-cli`). Each run has 10 minutes.
set -uo pipefail
dir=${1:?usage: $0 DIR [RNE]}
rne=${2:-target/release/rne}
cell() {
  local out status
  out=$(timeout 600 "$rne" stats "$@" --json 2>&1)
  status=$?
  if [ $status -eq 124 ]; then echo "timeout (600 s)"; return; fi
  if [ $status -ne 0 ]; then
    if grep -q "panicked\|RUST_BACKTRACE" <<<"$out"; then echo "**panic**"; return; fi
    echo "error: $(grep -m1 '^error' <<<"$out" | sed "s|^error: ||; s|$dir/||g; s/|/\\\\|/g" | cut -c1-200)"
    return
  fi
  python3 -c '
import json, sys
r = json.loads(sys.stdin.read().strip().splitlines()[-1])
u = r.get("undefined", [])
s = "%d kernels, %.2f s" % (len(r["kernels"]), r["generation_ms"] / 1e3)
if u: s += "; %d undefined (%s)" % (len(u), u[0]["reason"].replace("|", "\\|"))
print(s)' <<<"$out"
}
echo "| robot | own base | floating base |"
echo "|---|---|---|"
find "$dir" -name '*.urdf' | sort | while read -r urdf; do
  name=$(basename "$urdf" .urdf)
  echo "| $name | $(cell "$urdf") | $(cell "$urdf" --floating-base) |"
done
