"""The checked-in stubs equal what `python -m railcontact._generate` makes
of proto/ now (fails after a proto change until the stubs are regenerated)."""

from conftest import REPO
from railcontact import _generate

CHECKED_IN = REPO / "clients" / "python" / "src" / "railcontact" / "_proto"


def test_checked_in_stubs_match_the_proto(tmp_path):
    written = _generate.generate(REPO / "proto", tmp_path)
    names = sorted(p.name for p in written)
    assert names == sorted(p.name for p in CHECKED_IN.iterdir() if p.is_file()), "stub files differ"
    stale = [n for n in names if (tmp_path / n).read_text() != (CHECKED_IN / n).read_text()]
    assert not stale, (
        f"{stale} differ from proto/railcontact/v1/railcontact.proto: "
        "run `python -m railcontact._generate` and commit the result"
    )
