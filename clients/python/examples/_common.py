"""What every example shares: the command line, the connection, the
figure's output (matplotlib's Agg backend: no display needed) and Ctrl-C.

Ctrl-C stops an example cleanly: it closes its session, plots what it has
computed so far, writes the file and says so in one line (exit code 130),
instead of a traceback through gRPC's threads.
"""

from __future__ import annotations

import argparse
import signal
import sys

import matplotlib

matplotlib.use("Agg")
import matplotlib.pyplot as plt  # noqa: E402

import railcontact  # noqa: E402

#: The exit code after Ctrl-C (128 + SIGINT, as shells report it).
INTERRUPTED = 130


class StopOnCtrlC:
    """Ctrl-C as a request to stop between steps, for a loop of gRPC calls:
    the first SIGINT sets ``requested`` (the loop ends after the step in
    flight, so no call is broken off halfway and the session closes
    normally); a second one raises KeyboardInterrupt at once. The previous
    handler is back after the ``with`` block."""

    def __init__(self):
        self.requested = False
        self._previous = None

    def __enter__(self) -> "StopOnCtrlC":
        self._previous = signal.signal(signal.SIGINT, self._handle)
        return self

    def _handle(self, signum, frame) -> None:
        if self.requested:
            raise KeyboardInterrupt
        self.requested = True

    def __exit__(self, *exc) -> None:
        signal.signal(signal.SIGINT, self._previous)


def parser(doc: str, out: str) -> argparse.ArgumentParser:
    """An argument parser with ``--target`` and ``--out``; ``doc`` is the
    example's module docstring."""
    p = argparse.ArgumentParser(description=doc, formatter_class=argparse.RawDescriptionHelpFormatter)
    p.add_argument("--target", default="127.0.0.1:50051", help="server address HOST:PORT (default %(default)s)")
    p.add_argument("--out", default=out, help="PNG file to write (default %(default)s)")
    return p


def wheelrail_model(name: str) -> str:
    """An argparse type: a wheel/rail model name in any case, checked
    against :data:`railcontact.WHEELRAIL_MODELS`."""
    if name.lower() not in railcontact.WHEELRAIL_MODELS:
        raise argparse.ArgumentTypeError(f"{name!r} is not one of {', '.join(railcontact.WHEELRAIL_MODELS)}")
    return name.lower()


def connect(target: str) -> railcontact.Client:
    """A client, once the server answers."""
    client = railcontact.Client(target)
    client.wait_ready(10.0)
    return client


def save(fig, out: str, interrupted: str = "") -> None:
    """Writes ``fig`` to ``out`` and says so; ``interrupted`` (what was
    done when Ctrl-C came) makes that line say it holds only that much."""
    fig.tight_layout()
    fig.savefig(out, dpi=110)
    plt.close(fig)
    if interrupted:
        print(f"interrupted (Ctrl-C) after {interrupted}: wrote {out} with what was computed")
    else:
        print(f"wrote {out}")


def nothing_to_save(what: str) -> None:
    """Says in one line that Ctrl-C came before anything was computed, and
    exits with :data:`INTERRUPTED`."""
    print(f"interrupted (Ctrl-C) {what}: nothing computed, nothing written", file=sys.stderr)
    sys.exit(INTERRUPTED)
