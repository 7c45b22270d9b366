"""The real server for the tests: ``railcontact serve`` on an ephemeral
loopback port, started once per test session.

The binary is ``$RAILCONTACT_BIN`` (set by ``tests/end_to_end/python_client.rs`` to
cargo's build of it), else ``<repo>/target/debug/railcontact``. Its store
goes to a temporary directory; its log beside it, printed when the
server does not start.
"""

from __future__ import annotations

import os
import pathlib
import signal
import subprocess
import sys

import pytest

import railcontact

REPO = pathlib.Path(__file__).resolve().parents[3]
EXAMPLES = REPO / "clients" / "python" / "examples"


def _binary() -> pathlib.Path:
    path = pathlib.Path(os.environ.get("RAILCONTACT_BIN") or REPO / "target" / "debug" / "railcontact")
    if not path.is_file():
        pytest.fail(f"server binary {path} not found: run `cargo build` or set RAILCONTACT_BIN")
    return path


@pytest.fixture(scope="session")
def server(tmp_path_factory):
    """The address ``127.0.0.1:PORT`` of a running server."""
    yield from start_server(tmp_path_factory.mktemp("railcontact-data"))


def start_server(data_dir: pathlib.Path, *args: str):
    """Runs ``railcontact serve --listen 127.0.0.1:0 ARGS`` with its store
    in ``data_dir`` and its log beside it; yields its address, then stops
    it."""
    log_path = data_dir.parent / f"{data_dir.name}.log"
    env = dict(os.environ, RAILCONTACT_DATA_DIR=str(data_dir), RUST_LOG="warn")
    with open(log_path, "wb") as log:
        process = subprocess.Popen(
            [str(_binary()), "serve", "--listen", "127.0.0.1:0", *args],
            stdout=subprocess.PIPE,
            stderr=log,
            stdin=subprocess.DEVNULL,
            env=env,
        )
    try:
        line = process.stdout.readline().decode().strip()
        prefix = "railcontact listening on "
        if not line.startswith(prefix):
            process.kill()
            process.wait()
            pytest.fail(f"server did not start: {line!r}\n{log_path.read_text()}")
        yield line[len(prefix):]
    finally:
        process.send_signal(signal.SIGTERM)
        try:
            process.wait(timeout=20)
        except subprocess.TimeoutExpired:
            process.kill()
            process.wait()
        process.stdout.close()


@pytest.fixture(scope="session")
def client(server):
    """A client connected to the test server."""
    with railcontact.Client(server, timeout_s=120) as c:
        c.wait_ready(30)
        yield c


def steel() -> dict:
    return {"shear_modulus_pa": 81.0e9, "poisson_ratio": 0.30}


def rolling_case(model: str = "exact", n: int = 20, creepages=(1e-3, 5e-4, 0.0)) -> dict:
    """Steady rolling on the Hertz ellipse of examples/cases/hertz_ellipse_rolling.toml."""
    return {
        "model": model,
        "material": steel(),
        "friction": {"coefficient": 0.3},
        "geometry": {"kind": "quadratic", "a_per_m": 2.6, "b_per_m": 0.92},
        "load": {"normal_force_n": 1.0e4},
        "rolling": dict(zip(("creepage_long", "creepage_lat", "spin_per_m"), creepages)),
        "grid": {"nx": n, "ny": n},
    }


def run_cli(*args: str) -> subprocess.CompletedProcess:
    """Runs the command line of the server's binary (``railcontact ARGS``)."""
    return subprocess.run(
        [str(_binary()), *args], capture_output=True, text=True, timeout=300, stdin=subprocess.DEVNULL
    )


def run_example(name: str, server: str, out: pathlib.Path, *args: str) -> subprocess.CompletedProcess:
    """Runs ``examples/NAME`` against the test server, writing ``out``."""
    return subprocess.run(
        [sys.executable, str(EXAMPLES / name), "--target", server, "--out", str(out), *args],
        capture_output=True,
        text=True,
        timeout=300,
        env=dict(os.environ, MPLBACKEND="Agg"),
    )
