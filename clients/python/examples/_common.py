"""What every example shares: the command line, the connection and the
figure's output (matplotlib's Agg backend: no display needed)."""

from __future__ import annotations

import argparse

import matplotlib

matplotlib.use("Agg")
import matplotlib.pyplot as plt  # noqa: E402

import railcontact  # noqa: E402


def parser(doc: str, out: str) -> argparse.ArgumentParser:
    """An argument parser with ``--target`` and ``--out``; ``doc`` is the
    example's module docstring."""
    p = argparse.ArgumentParser(description=doc, formatter_class=argparse.RawDescriptionHelpFormatter)
    p.add_argument("--target", default="127.0.0.1:50051", help="server address HOST:PORT (default %(default)s)")
    p.add_argument("--out", default=out, help="PNG file to write (default %(default)s)")
    return p


def connect(target: str) -> railcontact.Client:
    """A client, once the server answers."""
    client = railcontact.Client(target)
    client.wait_ready(10.0)
    return client


def save(fig, out: str) -> None:
    fig.tight_layout()
    fig.savefig(out, dpi=110)
    plt.close(fig)
    print(f"wrote {out}")
