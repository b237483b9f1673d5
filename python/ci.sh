#!/usr/bin/env bash
# The Python package's CI: a fresh virtual environment with pinned maturin and pytest, the
# extension built into it by `maturin develop` (the dev profile of the repository's workspace,
# of which python/ is a member, in its target/ directory, with the features `cargo test
# --workspace` gives the crates they share: `workspace-features` in python/Cargo.toml), so
# that after `cargo test --workspace` cargo compiles only PyO3, rust-numpy and this crate
# again (their build scripts see maturin's environment); then pytest.
#
#   bash python/ci.sh            # from anywhere
#
# `pip install python/` (what a user runs; a release build) is the same crate in the release
# profile, without `workspace-features`. The bit-for-bit tests compare with the `rne` command
# of the same checkout: target/debug/rne (which `cargo test --workspace` builds) or $RNE_BIN;
# with CI=true they fail without it, elsewhere they are skipped. Talos's comparison with
# Pinocchio runs where example-robot-data is found (tests/test_pinocchio.py).
set -euo pipefail
cd "$(dirname "$0")"
root=$(cd .. && pwd)
venv=${RNE_PYTHON_VENV:-$root/target/python-ci-venv}
export CARGO_TARGET_DIR=${CARGO_TARGET_DIR:-$root/target}
python3 -m venv --clear "$venv"
"$venv/bin/python" -m pip install --quiet --upgrade pip
"$venv/bin/python" -m pip install --quiet maturin==1.16.0 pytest==9.2.0 "numpy>=1.21"
VIRTUAL_ENV="$venv" PATH="$venv/bin:$PATH" "$venv/bin/maturin" develop --quiet --features workspace-features
"$venv/bin/python" -c "import rne; print('rne', rne.__file__, rne.BUILTIN_ROBOTS)"
if [[ -z "${RNE_BIN:-}" && -x "$root/target/debug/rne" ]]; then
  export RNE_BIN="$root/target/debug/rne"
fi
if [[ "${CI:-}" == "true" ]]; then
  export RNE_REQUIRE_BIN=1
fi
# From the tests' folder, so that `import rne` is the installed package.
cd tests
"$venv/bin/python" -m pytest -q -p no:cacheprovider .
