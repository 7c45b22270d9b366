"""The examples run end to end against the test server (few points and
steps) and write their PNG."""

import pytest

from conftest import run_example

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
