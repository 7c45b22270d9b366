"""The one exception of the client: :class:`RailcontactError`."""

from __future__ import annotations

import re

import grpc

# The server's INVALID_ARGUMENT messages read "invalid `FIELD`: reason".
_FIELD_IN_MESSAGE = re.compile(r"^invalid `([^`]*)`: ")

_CODES_BY_NUMBER = {c.value[0]: c for c in grpc.StatusCode}


class RailcontactError(Exception):
    """A failed call, batch item or session step.

    Attributes:
        code: the gRPC status code (``grpc.StatusCode``), e.g.
            ``INVALID_ARGUMENT`` for a bad input, ``NOT_FOUND`` for an
            unknown profile pair, ``FAILED_PRECONDITION`` for a session step
            out of order.
        message: what went wrong and what to do (the server's text).
        field: path of the offending field in the request, e.g.
            ``case.geometry.a_per_m`` or ``step.velocity.forward_m_per_s``;
            empty when no single field is at fault.
    """

    def __init__(self, code: grpc.StatusCode, message: str, field: str = ""):
        super().__init__(f"{code.name}: {message}")
        self.code = code
        self.message = message
        self.field = field

    @classmethod
    def from_rpc(cls, error: grpc.RpcError) -> "RailcontactError":
        """The error of a failed call (the field parsed from the message)."""
        code = error.code() if hasattr(error, "code") else grpc.StatusCode.UNKNOWN
        message = error.details() if hasattr(error, "details") else str(error)
        message = message or ""
        match = _FIELD_IN_MESSAGE.match(message)
        return cls(code, message, match.group(1) if match else "")

    @classmethod
    def from_item(cls, item) -> "RailcontactError":
        """The error of a batch slot or a session response (an ``ItemError``)."""
        code = _CODES_BY_NUMBER.get(item.code, grpc.StatusCode.UNKNOWN)
        return cls(code, item.message, item.field)


def invalid(field: str, message: str) -> RailcontactError:
    """An INVALID_ARGUMENT raised by the client itself (before sending)."""
    return RailcontactError(grpc.StatusCode.INVALID_ARGUMENT, f"invalid `{field}`: {message}", field)
