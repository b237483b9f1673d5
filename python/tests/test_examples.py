"""The scripts of python/examples run as a user runs them (`python python/examples/NAME.py`,
with the installed rne) and print what each promises: the batch equal to a loop of single
calls, computed-torque control tracking its trajectory, identification predicting a fresh
record. A script that raises, or whose figure leaves its bound, fails here."""
import re
import subprocess
import sys
from pathlib import Path

EXAMPLES = Path(__file__).resolve().parents[1] / "examples"


def run(name):
    """The script's output; it must exit with 0."""
    done = subprocess.run([sys.executable, str(EXAMPLES / name)], capture_output=True,
                          text=True, timeout=600, cwd=EXAMPLES)
    assert done.returncode == 0, f"{name} failed:\n{done.stdout}\n{done.stderr}"
    return done.stdout


def number(pattern, text):
    """The float the first group of `pattern` matches in `text`."""
    found = re.search(pattern, text)
    assert found, f"no match for {pattern!r} in:\n{text}"
    return float(found.group(1))


def test_every_example_is_tested():
    assert sorted(p.name for p in EXAMPLES.glob("*.py")) == [
        "batch.py", "computed_torque.py", "identification.py"]


def test_the_batch_example_equals_its_loop_and_undoes_itself():
    out = run("batch.py")
    assert "batch == loop of single calls, bit for bit" in out
    assert number(r"forward dynamics undoes inverse dynamics: (\S+)", out) < 1e-10


def test_computed_torque_tracks_its_trajectory():
    out = run("computed_torque.py")
    assert number(r"largest tracking error after 1 s: (\S+) rad", out) < 1e-3


def test_identification_predicts_a_fresh_record():
    out = run("identification.py")
    assert number(r"RMS torque error (\S+) %", out) < 2.0
