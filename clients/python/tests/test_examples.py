"""The examples run end to end against the test server (few points and
steps) and write their PNG; Ctrl-C ends one cleanly with what it has."""

import os
import signal
import subprocess
import sys

import pytest

from conftest import EXAMPLES, run_example

SMOKE = {
    "creep_curve.py": ["--points", "3", "--models", "hertz_fastsim"],
    "patch_maps.py": ["--n", "12"],
    "conformal_models.py": ["--loads", "2", "--grid", "20", "26"],
    "wheelset_cosim.py": ["--steps", "12", "--jacobian-every", "5"],
}


@pytest.mark.parametrize("name", sorted(SMOKE))
def test_example_writes_its_png(name, server, tmp_path):
    out = tmp_path / name.replace(".py", ".png")
    done = run_example(name, server, out, *SMOKE[name])
    assert done.returncode == 0, f"{name} failed:\n{done.stdout}\n{done.stderr}"
    assert out.stat().st_size > 10_000 and out.read_bytes()[:4] == b"\x89PNG"
    assert f"wrote {out}" in done.stdout


def test_ctrl_c_closes_the_session_and_writes_what_was_computed(server, tmp_path):
    out = tmp_path / "cosim.png"
    example = EXAMPLES / "wheelset_cosim.py"
    args = ["--target", server, "--out", str(out), "--steps", "20000", "--jacobian-every", "100000"]
    # Ctrl-C's signal reaches it even where this test runs with SIGINT
    # ignored (a shell's background job): the child sets Python's own
    # handler before it runs the example. Not with preexec_fn: forking this
    # process (which holds gRPC) runs gRPC's fork handlers, which may write
    # to the child's stderr.
    start = (
        "import os, runpy, signal, sys; signal.signal(signal.SIGINT, signal.default_int_handler); "
        "sys.argv = sys.argv[1:]; sys.path.insert(0, os.path.dirname(sys.argv[0])); "
        "runpy.run_path(sys.argv[0], run_name='__main__')"
    )
    process = subprocess.Popen(
        [sys.executable, "-c", start, str(example), *args],
        stdout=subprocess.PIPE,
        stderr=subprocess.PIPE,
        text=True,
        env=dict(os.environ, MPLBACKEND="Agg"),
    )
    try:
        # Progress every 2000 steps: interrupted after the first 2000.
        assert process.stderr.readline().startswith("step 0 of 20000")
        assert process.stderr.readline().startswith("step 2000 of 20000")
        process.send_signal(signal.SIGINT)
        stdout, stderr = process.communicate(timeout=120)
    finally:
        if process.poll() is None:
            process.kill()
            process.communicate()
    assert process.returncode == 130, f"{stdout}\n{stderr}"
    assert "Traceback" not in stderr and stderr.strip() == "", stderr
    said = [line for line in stdout.splitlines() if line.startswith("interrupted")]
    assert len(said) == 1 and said[0].endswith(f"steps: wrote {out} with what was computed"), stdout
    assert out.read_bytes()[:4] == b"\x89PNG"
