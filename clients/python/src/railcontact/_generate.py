"""Regenerates the gRPC stubs in ``railcontact/_proto`` from ``proto/``.

The one command (from the repository root, in an environment with the
package's ``test`` extras, which pin grpcio-tools)::

    python -m railcontact._generate

``--proto-root DIR`` names another ``proto`` directory (default: the
repository's, found from this file) and ``--out DIR`` another output
directory (default: this package's ``_proto``). The drift test
(``tests/test_stubs.py``) generates into a temporary directory and compares
the result with the checked-in files.

protoc writes ``railcontact/v1/railcontact_pb2*.py`` whose grpc module imports
``railcontact.v1.railcontact_pb2``: that would resolve inside this package
(also named ``railcontact``), so the files are flattened into one directory
and the import made relative.
"""

from __future__ import annotations

import argparse
import pathlib
import sys
import tempfile

PROTO_FILE = "railcontact/v1/railcontact.proto"
PACKAGE_DIR = pathlib.Path(__file__).resolve().parent
DEFAULT_OUT = PACKAGE_DIR / "_proto"
# src/railcontact -> src -> clients/python -> clients -> the repository.
DEFAULT_PROTO_ROOT = PACKAGE_DIR.parents[3] / "proto"

GENERATED = ("railcontact_pb2.py", "railcontact_pb2.pyi", "railcontact_pb2_grpc.py")

INIT = '''"""Generated gRPC stubs of railcontact.v1 (do not edit).

Regenerate with ``python -m railcontact._generate``.
"""
'''

_ABSOLUTE_IMPORT = "from railcontact.v1 import railcontact_pb2 as"
_RELATIVE_IMPORT = "from . import railcontact_pb2 as"


def generate(proto_root: pathlib.Path = DEFAULT_PROTO_ROOT,
             out_dir: pathlib.Path = DEFAULT_OUT) -> list[pathlib.Path]:
    """Generates the stubs of ``proto_root``'s railcontact.proto into
    ``out_dir`` (created if missing); returns the files written."""
    from grpc_tools import protoc  # the test extras' grpcio-tools
    import importlib.resources

    proto_root = pathlib.Path(proto_root)
    out_dir = pathlib.Path(out_dir)
    if not (proto_root / PROTO_FILE).is_file():
        raise FileNotFoundError(f"{proto_root / PROTO_FILE} not found")
    well_known = str(importlib.resources.files("grpc_tools") / "_proto")
    with tempfile.TemporaryDirectory() as tmp:
        args = [
            "grpc_tools.protoc",
            f"-I{proto_root}",
            f"-I{well_known}",
            f"--python_out={tmp}",
            f"--pyi_out={tmp}",
            f"--grpc_python_out={tmp}",
            PROTO_FILE,
        ]
        if protoc.main(args) != 0:
            raise RuntimeError(f"protoc failed: {' '.join(args)}")
        out_dir.mkdir(parents=True, exist_ok=True)
        written = []
        for name in GENERATED:
            text = (pathlib.Path(tmp) / "railcontact" / "v1" / name).read_text()
            text = text.replace(_ABSOLUTE_IMPORT, _RELATIVE_IMPORT)
            (out_dir / name).write_text(text)
            written.append(out_dir / name)
    (out_dir / "__init__.py").write_text(INIT)
    written.append(out_dir / "__init__.py")
    return written


def main(argv: list[str] | None = None) -> int:
    parser = argparse.ArgumentParser(description=__doc__.splitlines()[0])
    parser.add_argument("--proto-root", type=pathlib.Path, default=DEFAULT_PROTO_ROOT)
    parser.add_argument("--out", type=pathlib.Path, default=DEFAULT_OUT)
    args = parser.parse_args(argv)
    for path in generate(args.proto_root, args.out):
        print(path)
    return 0


if __name__ == "__main__":
    sys.exit(main())
