#!/usr/bin/env bash
# The Python package's CI: a fresh virtual environment, `pip install python/` as a user would
# (pinned maturin from pyproject.toml, a release build of the extension), then its pytest tests.
#
#   bash python/ci.sh            # from anywhere; about 4 minutes on two cores from scratch
#
# The bit-for-bit tests compare with the `rne` command of the same checkout: target/debug/rne
# (which `cargo test --workspace` builds) or $RNE_BIN; with CI=true they fail without it,
# elsewhere they are skipped.
set -euo pipefail
cd "$(dirname "$0")"
root=$(cd .. && pwd)
venv=${RNE_PYTHON_VENV:-target/ci-venv}
python3 -m venv --clear "$venv"
"$venv/bin/python" -m pip install --quiet --upgrade pip
"$venv/bin/python" -m pip install --quiet pytest==9.2.0
# The extension's build is cargo's, in python/target: kept between runs.
log="$venv/install.log"
if ! "$venv/bin/python" -m pip install --verbose . > "$log" 2>&1; then
  tail -n 60 "$log"
  exit 1
fi
grep -E "Finished .release|Successfully installed" "$log" || true
"$venv/bin/python" -c "import rne; print('rne', rne.__file__)"
if [[ -z "${RNE_BIN:-}" && -x "$root/target/debug/rne" ]]; then
  export RNE_BIN="$root/target/debug/rne"
fi
if [[ "${CI:-}" == "true" ]]; then
  export RNE_REQUIRE_BIN=1
fi
# From the tests' folder, so that `import rne` is the installed package, not python/rne.
cd tests
"../$venv/bin/python" -m pytest -q -p no:cacheprovider .
