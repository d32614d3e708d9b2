"""What the Python package's tests share: the command-line tool that the
package must agree with, byte for byte, and the repository's data."""

import os
import pathlib
import subprocess

import pytest

ROOT = pathlib.Path(__file__).resolve().parents[2]
DATA = ROOT / "tests" / "data"


def tool() -> pathlib.Path:
    """The command-line tool `cargo test` built (or REDUNDANT_IK_BIN)."""
    path = pathlib.Path(os.environ.get("REDUNDANT_IK_BIN", ROOT / "target" / "debug" / "redundant-ik"))
    if not path.exists():
        pytest.fail(f"{path}: build the tool first (cargo build), or set REDUNDANT_IK_BIN")
    return path


def cli(*args: str) -> str:
    """What the tool prints for `args`; fails the test where it fails."""
    done = subprocess.run([str(tool()), *args], capture_output=True, text=True)
    assert done.returncode == 0, done.stderr
    return done.stdout


@pytest.fixture
def ctrl_c():
    """Python's own Ctrl-C handler for the test's duration. A runner started
    in the background (CI's) inherits SIGINT ignored, and then Python
    leaves it ignored and `_thread.interrupt_main()` does nothing."""
    import signal

    before = signal.signal(signal.SIGINT, signal.default_int_handler)
    yield
    signal.signal(signal.SIGINT, before)
