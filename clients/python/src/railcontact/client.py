"""The high-level client: :class:`Client` and its session objects."""

from __future__ import annotations

import os
import queue
import tomllib
from collections.abc import Callable, Iterable, Iterator, Mapping
from typing import Any, Optional, Union

import grpc

from ._build import build, enum_name, enum_names
from ._proto import railcontact_pb2 as pb
from ._proto import railcontact_pb2_grpc as pb_grpc
from .cases import WheelRailCase, load_wheelrail_case
from .errors import RailcontactError, invalid
from .results import (
    CreepCurvePoint,
    Grid,
    PatchResult,
    ProfilePairInfo,
    RegistrationProgress,
    SessionStepResult,
    WheelRailResult,
    WheelRailStepResult,
    fields_of,
    from_pb,
)

#: A patch case: a ``PatchCase`` message, a mapping with the keys of a
#: ``railcontact solve`` case file, or the path of such a TOML file.
CaseLike = Union[pb.PatchCase, Mapping, str, os.PathLike]

BUILTIN_PAIR = "mbench_s1002_uic60"
"""The server's built-in profile pair (S1002 wheel on UIC60 rail)."""

WHEELRAIL_MODELS: tuple = enum_names(pb.WheelRailModel.DESCRIPTOR)
"""The wheel/rail models ``model=`` takes (any case): ``exact``,
``hertz_fastsim``, ``cect``, ``auto``, ``hertz_fastsim_table``,
``hertz_polach``, ``hertz_fastsim_elliptic``, ``hertz_strip``,
``kik_piotrowski``, ``hertz_fastsim_modified``."""

PATCH_MODELS: tuple = enum_names(pb.Model.DESCRIPTOR)
"""The patch models of a patch case's ``model`` (any case): ``hertz``,
``hertz_corrected``, ``fastsim``, ``exact``, ``cect``, ``cect_halfspace``."""

#: A wheel/rail case: a :class:`WheelRailCase` or the path of a
#: ``railcontact wheelrail`` case file.
WheelRailCaseLike = Union[WheelRailCase, str, os.PathLike]


def load_case(path: Union[str, os.PathLike]) -> dict:
    """A case file of ``railcontact solve`` (TOML) as a mapping.

    A file of numerical influence coefficients the case names
    (``material.influence_file``, relative to the case file's directory)
    is read here and sent inline: the mapping holds its text as
    ``material.influence_file_content``, the wire's field (the server reads
    no file a client names).

    A file that cannot be read or is not TOML raises
    :class:`RailcontactError` (INVALID_ARGUMENT, field ``case``), like
    every other bad input; an influence-coefficient file that cannot be
    read, the same naming ``case.material.influence_file``.
    """
    try:
        with open(path, "rb") as f:
            case = tomllib.load(f)
    except (OSError, tomllib.TOMLDecodeError) as e:
        raise invalid("case", f"cannot read case file {os.fspath(path)}: {e}") from e
    return _inline_influence_file(case, os.path.dirname(os.fspath(path)))


def _inline_influence_file(case: Mapping, directory: Union[str, os.PathLike] = ".", path: str = "case") -> Mapping:
    """``case`` with the file its ``material.influence_file`` names (a path
    relative to ``directory``) read into ``material.influence_file_content``
    (UTF-8 text); ``case`` itself when it names none. Giving both keys, or
    a file that cannot be read, raises :class:`RailcontactError`
    (INVALID_ARGUMENT at ``PATH.material.influence_file``)."""
    material = case.get("material") if isinstance(case, Mapping) else None
    if not isinstance(material, Mapping) or "influence_file" not in material:
        return case
    key = f"{path}.material.influence_file"
    material = dict(material)
    name = material.pop("influence_file")
    if "influence_file_content" in material:
        raise invalid(key, "give either influence_file (a path) or influence_file_content (its text), not both")
    file = os.path.join(directory, os.fspath(name))
    try:
        with open(file, encoding="utf-8") as f:
            material["influence_file_content"] = f.read()
    except (OSError, UnicodeDecodeError, TypeError) as e:
        raise invalid(key, f"cannot read the influence-coefficient file {file}: {e}") from e
    return {**case, "material": material}


def patch_case(case: CaseLike, path: str = "case") -> pb.PatchCase:
    """A ``PatchCase`` message from a message, a mapping or a TOML file.
    A wheel/rail case (with ``track`` and ``wheelset``) raises
    :class:`RailcontactError` pointing to :meth:`Client.solve_wheelrail_case`."""
    if isinstance(case, (str, os.PathLike)):
        case = load_case(case)
    if isinstance(case, Mapping) and "track" in case and "wheelset" in case:
        raise invalid(
            path,
            "a wheel/rail case (`railcontact wheelrail`, with [track] and [wheelset]): solve it with "
            "Client.solve_wheelrail_case, or read it with railcontact.load_wheelrail_case",
        )
    return build(pb.PatchCase, _inline_influence_file(case, ".", path), path)


def _call(function, *args, **kwargs):
    """Calls a stub method, raising RailcontactError for a failed status."""
    try:
        return function(*args, **kwargs)
    except grpc.RpcError as e:
        raise RailcontactError.from_rpc(e) from None


def _stream(responses: Iterator) -> Iterator:
    """The messages of a server stream, raising RailcontactError for a
    failed status."""
    try:
        yield from responses
    except grpc.RpcError as e:
        raise RailcontactError.from_rpc(e) from None


class _Bearer(
    grpc.UnaryUnaryClientInterceptor,
    grpc.UnaryStreamClientInterceptor,
    grpc.StreamUnaryClientInterceptor,
    grpc.StreamStreamClientInterceptor,
):
    """Adds ``authorization: Bearer TOKEN`` to the metadata of every call."""

    def __init__(self, token: str):
        self._entry = ("authorization", f"Bearer {token}")

    def _details(self, details):
        return _Details(details, list(details.metadata or []) + [self._entry])

    def intercept_unary_unary(self, continuation, details, request):
        return continuation(self._details(details), request)

    def intercept_unary_stream(self, continuation, details, request):
        return continuation(self._details(details), request)

    def intercept_stream_unary(self, continuation, details, requests):
        return continuation(self._details(details), requests)

    def intercept_stream_stream(self, continuation, details, requests):
        return continuation(self._details(details), requests)


class _Details(grpc.ClientCallDetails):
    """``details`` with other metadata."""

    def __init__(self, details, metadata):
        self.method = details.method
        self.timeout = details.timeout
        self.metadata = metadata
        self.credentials = details.credentials
        self.wait_for_ready = getattr(details, "wait_for_ready", None)
        self.compression = getattr(details, "compression", None)


def _read(path) -> bytes:
    with open(path, "rb") as f:
        return f.read()


class Client:
    """A connection to a railcontact server.

    ``Client("127.0.0.1:50051")`` opens an insecure channel; use it as a
    context manager (or call :meth:`close`). ``tls=True`` connects with TLS
    trusting the system's authorities, ``tls="ca.pem"`` trusting those of
    that PEM file; ``client_cert=("client.pem", "client-key.pem")`` presents
    a client certificate (mutual TLS). ``token`` is sent on every call as
    ``authorization: Bearer TOKEN`` (servers with ``auth_tokens_file``). ``timeout_s`` is the deadline of
    each unary call and server stream (None: none). ``client.stub`` is the
    generated ``ContactServiceStub`` and ``railcontact.pb`` the message
    module, for everything this API does not cover.

    Every failure raises :class:`railcontact.RailcontactError`.

    Pairs this client registered are registered again, once, when a
    wheel/rail call on one of them answers NOT_FOUND (a registration reaches
    one replica behind a balancer; a server restarted without its store),
    and the call is retried; a pair this client deleted is not.
    """

    def __init__(
        self,
        target: str = "127.0.0.1:50051",
        *,
        timeout_s: Optional[float] = None,
        options: Optional[list] = None,
        channel: Optional[grpc.Channel] = None,
        tls: Union[bool, str, os.PathLike, None] = None,
        client_cert: Optional[tuple] = None,
        token: Optional[str] = None,
    ):
        max_message = 256 * 1024 * 1024
        default_options = [
            ("grpc.max_receive_message_length", max_message),
            ("grpc.max_send_message_length", max_message),
        ]
        self.target = target
        self.timeout_s = timeout_s
        options = options or default_options
        if channel is None:
            if tls or client_cert:
                root = None if tls is True or not tls else _read(tls)
                key, chain = (None, None)
                if client_cert:
                    chain, key = _read(client_cert[0]), _read(client_cert[1])
                credentials = grpc.ssl_channel_credentials(
                    root_certificates=root, private_key=key, certificate_chain=chain
                )
                channel = grpc.secure_channel(target, credentials, options=options)
            else:
                channel = grpc.insecure_channel(target, options=options)
        if token:
            channel = grpc.intercept_channel(channel, _Bearer(token))
        self.channel = channel
        self.stub = pb_grpc.ContactServiceStub(self.channel)
        # Pair id -> the RegisterProfilePairRequest that registered it.
        self._registrations: dict = {}

    def close(self) -> None:
        """Closes the channel."""
        self.channel.close()

    def __enter__(self) -> "Client":
        return self

    def __exit__(self, *exc) -> None:
        self.close()

    def wait_ready(self, timeout_s: float = 10.0) -> None:
        """Blocks until the channel is connected (RailcontactError
        UNAVAILABLE after ``timeout_s``)."""
        try:
            grpc.channel_ready_future(self.channel).result(timeout=timeout_s)
        except grpc.FutureTimeoutError:
            raise RailcontactError(
                grpc.StatusCode.UNAVAILABLE, f"no server at {self.target} after {timeout_s} s"
            ) from None

    # -- patches -------------------------------------------------------

    def solve_patch(
        self, case: CaseLike, *, include_fields: bool = False, include_sensitivities: bool = False
    ) -> PatchResult:
        """Solves one contact patch (``SolvePatch``).

        ``case`` mirrors the case file of ``railcontact solve`` (see
        ``examples/cases/README.md``), e.g.::

            {"model": "exact",
             "material": {"shear_modulus_pa": 81e9, "poisson_ratio": 0.3},
             "friction": {"coefficient": 0.3},
             "geometry": {"kind": "quadratic", "a_per_m": 2.6, "b_per_m": 0.92},
             "load": {"normal_force_n": 1e4},
             "rolling": {"creepage_long": 1e-3},
             "grid": {"nx": 24, "ny": 24}}

        ``include_fields`` adds the per-element fields (exact and conformal
        models) as ``result.fields``; ``include_sensitivities`` the force
        Jacobian as ``result.result.sensitivities``.
        """
        request = pb.SolvePatchRequest(
            case=patch_case(case),
            include_fields=include_fields,
            include_sensitivities=include_sensitivities,
        )
        response = _call(self.stub.SolvePatch, request, timeout=self.timeout_s)
        return PatchResult.from_pb(response.result)

    def solve_patch_batch(
        self, cases: Iterable[CaseLike], *, include_fields: bool = False
    ) -> list:
        """Solves many patches in parallel (``SolvePatchBatch``). Returns one
        entry per case in order: a :class:`PatchResult`, or the
        :class:`RailcontactError` of a failed item (not raised)."""
        items = [
            pb.SolvePatchRequest(case=patch_case(c, f"items[{i}].case"), include_fields=include_fields)
            for i, c in enumerate(cases)
        ]
        response = _call(self.stub.SolvePatchBatch, pb.SolvePatchBatchRequest(items=items), timeout=self.timeout_s)
        return [
            PatchResult.from_pb(item.result)
            if item.WhichOneof("outcome") == "result"
            else RailcontactError.from_item(item.error)
            for item in response.items
        ]

    def creep_curve(
        self,
        case: CaseLike,
        creepages: Optional[Iterable] = None,
        *,
        linear: Optional[tuple] = None,
        include_fields: bool = False,
    ) -> Iterator[CreepCurvePoint]:
        """A steady-rolling creep-force curve (``CreepCurve``), one
        :class:`CreepCurvePoint` per point, in order, as the server streams
        them.

        Give either ``creepages``, a list of points (each
        ``(creepage_long, creepage_lat, spin_per_m)`` or a mapping), or
        ``linear=(from, to, points)`` for evenly spaced points. ``case`` must
        be a rolling case (models exact, fastsim, cect, cect_halfspace).
        """
        request = pb.CreepCurveRequest(case=patch_case(case), include_fields=include_fields)
        if (creepages is None) == (linear is None):
            raise ValueError("give exactly one of `creepages` and `linear`")
        if creepages is not None:
            for i, c in enumerate(creepages):
                request.list.points.append(build(pb.Creepages, c, f"list.points[{i}]"))
        else:
            start, end, points = linear
            request.linear.CopyFrom(build(pb.LinearSweep, {"from": start, "to": end, "points": points}, "linear"))
        for point in _stream(_call(self.stub.CreepCurve, request, timeout=self.timeout_s)):
            yield from_pb(CreepCurvePoint, point)

    def patch_session(
        self,
        case: CaseLike,
        *,
        include_fields: bool = False,
        include_sensitivities: bool = False,
        label: str = "",
    ) -> "PatchSession":
        """Opens a co-simulation session on one patch (``PatchSession``); see
        :class:`PatchSession`. The case's kinematics fix the session kind:
        ``rolling`` (steps give creepages), ``transient`` (steps give
        shifts) or neither (steps give loads)."""
        request = pb.SessionRequest(
            open=pb.SessionOpen(
                case=patch_case(case, "open.case"),
                include_fields=include_fields,
                include_sensitivities=include_sensitivities,
                client_label=label,
            )
        )
        return PatchSession(self.stub.PatchSession, request)

    # -- profile pairs ---------------------------------------------------

    def register_pair(
        self,
        spec: Union[pb.ProfilePairSpec, Mapping, None] = None,
        *,
        builtin: str = "",
        label: str = "",
        progress: Optional[Callable[[RegistrationProgress], Any]] = None,
    ) -> ProfilePairInfo:
        """Registers a profile pair (``RegisterProfilePair``) and returns it
        once READY. ``spec`` mirrors ``ProfilePairSpec`` (profiles as
        ``{"builtin_name": ...}`` or ``{"file": {"content": ...,
        "file_name": ...}}``, ``track``, ``wheelset``, ...), or ``builtin``
        names a built-in pair. ``progress`` is called with every
        :class:`RegistrationProgress`. Registering equal inputs again
        returns the same pair at once."""
        if (spec is None) == (not builtin):
            raise ValueError("give exactly one of `spec` and `builtin`")
        request = pb.RegisterProfilePairRequest(label=label)
        if builtin:
            request.builtin_pair = builtin
        else:
            request.spec.CopyFrom(build(pb.ProfilePairSpec, spec, "spec"))
        info = self._register(request, progress)
        self._registrations[info.pair_id] = request
        return info

    def _register(self, request: pb.RegisterProfilePairRequest, progress=None) -> ProfilePairInfo:
        """Sends a registration; its READY pair."""
        last = None
        for message in _stream(_call(self.stub.RegisterProfilePair, request, timeout=self.timeout_s)):
            last = from_pb(RegistrationProgress, message)
            if progress is not None:
                progress(last)
        if last is None or last.pair is None:
            raise RailcontactError(grpc.StatusCode.INTERNAL, "registration ended without READY")
        return last.pair

    def get_pair(self, pair_id: str) -> ProfilePairInfo:
        """Describes one pair (by id or built-in name)."""
        message = _call(self.stub.GetProfilePair, pb.GetProfilePairRequest(pair_id=pair_id), timeout=self.timeout_s)
        return from_pb(ProfilePairInfo, message)

    def list_pairs(self) -> list:
        """Every registered pair, ordered by id."""
        response = _call(self.stub.ListProfilePairs, pb.ListProfilePairsRequest(), timeout=self.timeout_s)
        return [from_pb(ProfilePairInfo, p) for p in response.pairs]

    def delete_pair(self, pair_id: str) -> None:
        """Removes a pair (not a built-in one)."""
        self._registrations.pop(pair_id, None)
        _call(self.stub.DeleteProfilePair, pb.DeleteProfilePairRequest(pair_id=pair_id), timeout=self.timeout_s)

    # -- wheelsets ---------------------------------------------------------

    def solve_wheelrail(
        self,
        pair_id: str = BUILTIN_PAIR,
        *,
        velocity,
        load,
        position=None,
        model="exact",
        sides="both",
        friction=None,
        element_size_m: Optional[float] = None,
        min_elements_across: Optional[int] = None,
        force_tolerance_of_wheel_load: Optional[float] = None,
        include_fields: bool = False,
        temperature=None,
        friction_table=None,
        polach=None,
        modified_fastsim=None,
        conformal=None,
    ) -> WheelRailResult:
        """Solves a wheelset on a registered pair (``SolveWheelRail``).

        ``position``: mapping of ``WheelsetPosition`` (``lateral_m``,
        ``yaw_rad``, ``roll_rad``; default centred); ``velocity``: of
        ``WheelsetVelocity`` (``forward_m_per_s`` required, < 0 rolling
        backwards, ...; on a
        roller rig ``roller_rad_per_s`` required, the forward speed usually
        0), or a number: the forward speed; ``load``: of ``WheelLoad``
        (``vertical_force_n``, ``approach_m`` or ``center_z_m``, the
        wheelset centre's height as an MBS integrator has it; with
        ``total_longitudinal_force_n`` [N] the pitch rate is found for that
        traction (< 0) or braking (> 0) force, see
        ``WheelRailResult.pitch_control``), or a number: the vertical force
        per wheel [N]; ``model``: one of :data:`WHEELRAIL_MODELS` in any
        case, ``"exact"``, ``"hertz_fastsim"``, ``"cect"``, ``"auto"``,
        ``"hertz_fastsim_table"``, ``"hertz_polach"``,
        ``"hertz_fastsim_elliptic"``, ``"hertz_strip"``,
        ``"kik_piotrowski"`` or ``"hertz_fastsim_modified"`` (see the
        README's table of models); ``sides``:
        ``"both"``, ``"left"``, ``"right"``; ``friction``: a coefficient or a
        ``FrictionSection`` mapping (default: the pair's); ``temperature``:
        a ``TemperatureSection`` mapping (``body1``: the rail, ``body2``: the
        wheel, each ``bulk_temperature_k``, ``conductivity_w_per_m_k``,
        ``density_kg_per_m3``, ``specific_heat_j_per_kg_k``; models
        ``"exact"``, ``"cect"``, ``"auto"``): each patch's flash
        temperatures in ``WheelRailPatch.temperature``; ``friction_table``:
        a ``FrictionTable`` mapping (coefficients over the rail profile's
        contact angles or lateral coordinates, and along the track);
        ``polach``, ``modified_fastsim``: the parameters of the models
        ``"hertz_polach"`` and ``"hertz_fastsim_modified"``
        (``PolachParameters``, ``ModifiedFastsimParameters``);
        ``conformal``: ``{"rigid_slip": ...}`` of the models ``"cect"`` and
        ``"auto"``; ``min_elements_across``: a patch of the models
        ``"exact"``, ``"cect"``, ``"auto"`` expected narrower than this many
        elements is solved on elements 2-4 times narrower along s (default
        8; 0 never narrows them, CONTACT's DX by DS);
        ``force_tolerance_of_wheel_load`` (model ``"exact"``, 5e-3 to 0.1):
        each wheel's patches on elements up to 2.5 times
        ``element_size_m`` where its forces stay within that fraction of
        its vertical force of those on ``element_size_m`` (checked on
        both grids; see the proto's field). :meth:`solve_wheelrail_case`
        takes them all from a case file of ``railcontact wheelrail``.
        """
        request = wheelrail_request(
            pair_id,
            position=position,
            velocity=velocity,
            load=load,
            model=model,
            sides=sides,
            friction=friction,
            element_size_m=element_size_m,
            min_elements_across=min_elements_across,
            force_tolerance_of_wheel_load=force_tolerance_of_wheel_load,
            include_fields=include_fields,
            temperature=temperature,
            friction_table=friction_table,
            polach=polach,
            modified_fastsim=modified_fastsim,
            conformal=conformal,
        )
        response = self._on_pair(
            pair_id, lambda: _call(self.stub.SolveWheelRail, request, timeout=self.timeout_s)
        )
        return from_pb(WheelRailResult, response.result)

    def _on_pair(self, pair_id: str, call: Callable[[], Any]) -> Any:
        """``call()``; registers the pair again and retries once when it
        answers NOT_FOUND for a pair this client registered."""
        try:
            return call()
        except RailcontactError as e:
            request = self._registrations.get(pair_id)
            if e.code != grpc.StatusCode.NOT_FOUND or request is None:
                raise
            self._register(request)
            return call()

    def solve_wheelrail_case(self, case: WheelRailCaseLike, **overrides: Any) -> WheelRailResult:
        """Solves a ``railcontact wheelrail`` case file as the command line
        does, with the same forces: registers its profile pair (once per
        client: a pair this client registered with the same profiles is
        reused) and solves its motion with its settings.

        ``case`` is the file's path or a :class:`WheelRailCase` of
        :func:`load_wheelrail_case`; ``overrides`` replace the case's
        keyword arguments of :meth:`solve_wheelrail` (``model=``,
        ``position=``, ``include_fields=True``, ...)::

            r = client.solve_wheelrail_case("examples/cases/wheelset_a22.toml")
            print(r.wheel("right").force_track_n)
        """
        if not isinstance(case, WheelRailCase):
            case = load_wheelrail_case(case)
        pair_id = self._registered_pair(case)
        return self.solve_wheelrail(pair_id, **case.solve_arguments(**overrides))

    def _registered_pair(self, case: WheelRailCase) -> str:
        """The id of ``case``'s pair: one this client registered with the
        same spec, else registered now."""
        spec = build(pb.ProfilePairSpec, case.pair, "pair")
        for pair_id, request in self._registrations.items():
            if request.HasField("spec") and request.spec == spec:
                return pair_id
        return self.register_pair(spec, label=case.label).pair_id

    def solve_wheelrail_batch(self, queries: Iterable[Union[Mapping, pb.SolveWheelRailRequest]]) -> list:
        """Solves many wheelset queries in parallel. Each query is a
        mapping of :meth:`solve_wheelrail`'s keyword arguments (plus
        ``pair_id``) or a ``SolveWheelRailRequest``. Returns one entry per
        query: a :class:`WheelRailResult` or the item's
        :class:`RailcontactError`."""
        items = [
            q if isinstance(q, pb.SolveWheelRailRequest) else wheelrail_request(path=f"items[{i}]", **q)
            for i, q in enumerate(queries)
        ]
        response = _call(
            self.stub.SolveWheelRailBatch, pb.SolveWheelRailBatchRequest(items=items), timeout=self.timeout_s
        )
        return [
            from_pb(WheelRailResult, item.result)
            if item.WhichOneof("outcome") == "result"
            else RailcontactError.from_item(item.error)
            for item in response.items
        ]

    def wheelrail_session(
        self,
        pair_id: str = BUILTIN_PAIR,
        *,
        model="exact",
        sides="both",
        friction=None,
        element_size_m: Optional[float] = None,
        min_elements_across: Optional[int] = None,
        force_tolerance_of_wheel_load: Optional[float] = None,
        include_fields: bool = False,
        label: str = "",
        temperature=None,
        friction_table=None,
        polach=None,
        modified_fastsim=None,
        conformal=None,
    ) -> "WheelRailSession":
        """Opens a co-simulation session on a wheelset (``WheelRailSession``);
        see :class:`WheelRailSession`. The settings hold for every step
        (``model``, ``temperature``, ``friction_table``, ``polach``,
        ``modified_fastsim`` and ``conformal`` as in :meth:`solve_wheelrail`;
        a case file's are ``WheelRailCase.settings``)."""
        values = _set_values(
            pair_id=pair_id,
            model=model,
            sides=sides,
            friction=friction,
            element_size_m=element_size_m,
            min_elements_across=min_elements_across,
            force_tolerance_of_wheel_load=force_tolerance_of_wheel_load,
            include_fields=include_fields,
            client_label=label,
            temperature=temperature,
            friction_table=friction_table,
            polach=polach,
            modified_fastsim=modified_fastsim,
            conformal=conformal,
        )
        opening = build(pb.WheelRailSessionOpen, values, "open")
        return self._on_pair(
            pair_id,
            lambda: WheelRailSession(self.stub.WheelRailSession, pb.WheelRailSessionRequest(open=opening)),
        )


def wheelrail_request(
    pair_id: str = BUILTIN_PAIR, *, path: str = "", velocity=None, load=None, **settings
) -> pb.SolveWheelRailRequest:
    """A ``SolveWheelRailRequest`` from :meth:`Client.solve_wheelrail`'s
    arguments (``None`` values left unset)."""
    values = _set_values(pair_id=pair_id, velocity=velocity, load=load, **settings)
    return build(pb.SolveWheelRailRequest, values, path)


def _set_values(**values) -> dict:
    """The values that are not None (the others stay unset)."""
    return {k: v for k, v in values.items() if v is not None}


class _Session:
    """A bidirectional stream driven one request, one response at a time."""

    _request_class: Any = None
    _response_class: Any = None

    def __init__(self, method, opening):
        self._requests: "queue.Queue" = queue.Queue()
        self._requests.put(opening)
        self._responses = method(self._request_iterator())
        self._closed = False
        self.next_step_index = 0
        try:
            opened = self._receive("opened")
        except BaseException as e:
            if not isinstance(e, RailcontactError):
                self._abort()  # Ctrl-C while opening
            raise
        self.session_id: str = opened.session_id
        self._opened(opened)

    def _opened(self, opened) -> None:
        """Keeps what the opening answer says (subclasses)."""

    def _request_iterator(self):
        while True:
            request = self._requests.get()
            if request is None:
                return
            yield request

    def _receive(self, expected: str):
        try:
            response = next(self._responses)
        except StopIteration:
            raise RailcontactError(grpc.StatusCode.UNAVAILABLE, "the session stream ended") from None
        except grpc.RpcError as e:
            self._closed = True
            self._requests.put(None)  # ends the request iterator's thread
            raise RailcontactError.from_rpc(e) from None
        kind = response.WhichOneof("kind")
        if kind == "error":
            raise RailcontactError.from_item(response.error)
        if kind != expected:
            raise RailcontactError(grpc.StatusCode.INTERNAL, f"expected `{expected}`, got `{kind}`")
        return getattr(response, kind)

    def _exchange(self, request, expected: str):
        if self._closed:
            raise RailcontactError(grpc.StatusCode.FAILED_PRECONDITION, "the session is closed")
        self._requests.put(request)
        try:
            return self._receive(expected)
        except BaseException as e:
            # Interrupted (Ctrl-C) while the server answers: the answer would
            # be taken for the next request's, so the session ends here.
            if not isinstance(e, RailcontactError):
                self._abort()
            raise

    def _abort(self) -> None:
        """Cancels the stream at once (the server closes the session): after
        an exception in a ``with`` block or an interrupted exchange. Later
        steps raise FAILED_PRECONDITION."""
        if self._closed:
            return
        self._closed = True
        self._requests.put(None)  # ends the request iterator's thread
        self._responses.cancel()

    def _step(self, step_class, step_index: Optional[int], **values):
        """Sends one step (index: the next one unless given) and returns the
        server's step result message."""
        index = self.next_step_index if step_index is None else step_index
        request = build(step_class, _set_values(step_index=index, **values), "step")
        step = self._exchange(self._request_class(step=request), "step")
        self.next_step_index = step.step_index + 1
        return step

    def rollback(self, to_step_index: int) -> int:
        """Goes back to the state after the marked step ``to_step_index``
        (marks after it are dropped); returns the next step's index,
        ``to_step_index + 1``. An unknown mark raises RailcontactError
        (FAILED_PRECONDITION) and leaves the session as it was."""
        rolled = self._exchange(
            self._request_class(rollback=pb.SessionRollback(to_step_index=to_step_index)), "rolled_back"
        )
        self.next_step_index = rolled.next_step_index
        return rolled.next_step_index

    def close(self) -> None:
        """Ends the stream (the server closes the session)."""
        if self._closed:
            return
        self._closed = True
        self._requests.put(None)
        try:
            for _ in self._responses:
                pass
        except grpc.RpcError:
            pass

    def __enter__(self):
        return self

    def __exit__(self, exc_type, *exc) -> None:
        if exc_type is not None:
            self._abort()
        self.close()


class PatchSession(_Session):
    """A co-simulation session on one patch (from :meth:`Client.patch_session`).

    Each :meth:`step` sends one ``SessionStep`` and returns its
    :class:`SessionStepResult`; step indices are counted for you (after
    ``rollback(k)`` the next one is ``k + 1``). A refused step or rollback
    raises :class:`RailcontactError` and the session stays open.
    Attributes after opening: ``session_id``, ``model``, ``grid``, ``notes``.
    """

    _request_class = pb.SessionRequest

    def _opened(self, opened) -> None:
        self.model: str = enum_name(pb.Model.DESCRIPTOR, opened.model)
        self.grid: Optional[Grid] = from_pb(Grid, opened.grid) if opened.HasField("grid") else None
        self.notes: tuple = tuple(opened.notes)

    def step(
        self,
        creepages=None,
        *,
        normal_force_n: Optional[float] = None,
        approach_m: Optional[float] = None,
        shift=None,
        time_s: float = 0.0,
        mark: bool = False,
        step_index: Optional[int] = None,
    ) -> SessionStepResult:
        """Solves the next step.

        ``creepages`` (rolling sessions): ``(creepage_long, creepage_lat,
        spin_per_m)`` or a mapping; ``normal_force_n`` or ``approach_m``: the
        step's load (default: the case's); ``shift`` (transient sessions):
        a ``ShiftStep`` mapping (``shift_x_m``, ``shift_y_m``,
        ``rotation_rad``; or ``creepage_long``, ``creepage_lat``,
        ``spin_per_m`` for a step that rolls the case's
        ``transient.rolling_step_m``); ``mark``: remember the state after this step for
        :meth:`rollback`; ``step_index``: default the next one.
        """
        step = self._step(
            pb.SessionStep,
            step_index,
            time_s=time_s,
            normal_force_n=normal_force_n,
            approach_m=approach_m,
            creepages=creepages,
            shift=shift,
            mark=mark,
        )
        return from_pb(SessionStepResult, step, fields=fields_of(step, self.grid))


class WheelRailSession(_Session):
    """A co-simulation session on a wheelset (from
    :meth:`Client.wheelrail_session`).

    ::

        with client.wheelrail_session("mbench_s1002_uic60", model="hertz_fastsim") as s:
            r = s.step(position={"lateral_m": 0.003},
                       velocity={"forward_m_per_s": 30.0}, load=1e5, mark=True)
            ...
            s.rollback(0)

    Attributes after opening: ``session_id``, ``pair_id`` (resolved),
    ``model``.
    """

    _request_class = pb.WheelRailSessionRequest

    def _opened(self, opened) -> None:
        self.pair_id: str = opened.pair_id
        self.model: str = enum_name(pb.WheelRailModel.DESCRIPTOR, opened.model)

    def step(
        self,
        *,
        velocity,
        load,
        position=None,
        time_s: float = 0.0,
        mark: bool = False,
        step_index: Optional[int] = None,
    ) -> WheelRailStepResult:
        """Solves the next step: ``position`` (``WheelsetPosition`` mapping,
        default centred), ``velocity`` (``WheelsetVelocity`` mapping or the
        forward speed), ``load`` (``WheelLoad`` mapping or the vertical force
        per wheel [N]); ``mark`` and ``step_index`` as in
        :meth:`PatchSession.step`."""
        step = self._step(
            pb.WheelRailSessionStep,
            step_index,
            time_s=time_s,
            position=position,
            velocity=velocity,
            load=load,
            mark=mark,
        )
        return from_pb(WheelRailStepResult, step)
