"""TLS and bearer tokens: a server with ``--tls-cert``, ``--tls-key`` and
``--auth-tokens-file`` (certificates made here), reached with
``Client(..., tls=CA_FILE, token=...)``."""

from __future__ import annotations

import datetime
import hashlib
import ipaddress

import grpc
import pytest
from conftest import rolling_case, start_server
from cryptography import x509
from cryptography.hazmat.primitives import hashes, serialization
from cryptography.hazmat.primitives.asymmetric import ec
from cryptography.x509.oid import NameOID

import railcontact

SOLVE_TOKEN = "python-solve-token-0123"
ADMIN_TOKEN = "python-admin-token-4567"


def _pem(path, obj) -> str:
    if isinstance(obj, x509.Certificate):
        data = obj.public_bytes(serialization.Encoding.PEM)
    else:
        data = obj.private_bytes(
            serialization.Encoding.PEM,
            serialization.PrivateFormat.PKCS8,
            serialization.NoEncryption(),
        )
    path.write_bytes(data)
    return str(path)


def _certificates(directory):
    """A CA and a server certificate for localhost and 127.0.0.1; the paths
    of the CA, the certificate and its key."""
    now = datetime.datetime.now(datetime.timezone.utc)
    ca_key = ec.generate_private_key(ec.SECP256R1())
    ca_name = x509.Name([x509.NameAttribute(NameOID.COMMON_NAME, "railcontact test CA")])
    ca = (
        x509.CertificateBuilder()
        .subject_name(ca_name)
        .issuer_name(ca_name)
        .public_key(ca_key.public_key())
        .serial_number(x509.random_serial_number())
        .not_valid_before(now - datetime.timedelta(hours=1))
        .not_valid_after(now + datetime.timedelta(days=1))
        .add_extension(x509.BasicConstraints(ca=True, path_length=None), critical=True)
        .sign(ca_key, hashes.SHA256())
    )
    key = ec.generate_private_key(ec.SECP256R1())
    cert = (
        x509.CertificateBuilder()
        .subject_name(x509.Name([x509.NameAttribute(NameOID.COMMON_NAME, "localhost")]))
        .issuer_name(ca_name)
        .public_key(key.public_key())
        .serial_number(x509.random_serial_number())
        .not_valid_before(now - datetime.timedelta(hours=1))
        .not_valid_after(now + datetime.timedelta(days=1))
        .add_extension(
            x509.SubjectAlternativeName(
                [x509.DNSName("localhost"), x509.IPAddress(ipaddress.ip_address("127.0.0.1"))]
            ),
            critical=False,
        )
        .sign(ca_key, hashes.SHA256())
    )
    return (
        _pem(directory / "ca.pem", ca),
        _pem(directory / "server.pem", cert),
        _pem(directory / "server-key.pem", key),
    )


@pytest.fixture(scope="module")
def secure(tmp_path_factory):
    """The address ``localhost:PORT`` of a server with TLS and tokens, and
    the CA file."""
    directory = tmp_path_factory.mktemp("tls")
    ca, cert, key = _certificates(directory)
    tokens = directory / "tokens.toml"
    tokens.write_text(
        f'[[token]]\nname = "py-solve"\nrole = "solve"\ntoken = "{SOLVE_TOKEN}"\n\n'
        f'[[token]]\nname = "py-admin"\nrole = "admin"\n'
        f'sha256 = "{hashlib.sha256(ADMIN_TOKEN.encode()).hexdigest()}"\n'
    )
    args = ["--tls-cert", cert, "--tls-key", key, "--auth-tokens-file", str(tokens)]
    for address in start_server(tmp_path_factory.mktemp("secure-data"), *args):
        yield address.replace("127.0.0.1", "localhost"), ca


def test_tls_and_a_solve_token_solve(secure):
    target, ca = secure
    with railcontact.Client(target, tls=ca, token=SOLVE_TOKEN, timeout_s=60) as c:
        r = c.solve_patch(rolling_case("fastsim"))
        assert r.result.totals.normal_force_n > 0
        with c.patch_session(rolling_case("fastsim")) as s:
            assert s.step((1e-3, 0.0, 0.0)).result.totals.normal_force_n > 0
        assert c.list_pairs()


def test_missing_token_and_roles_are_refused(secure):
    target, ca = secure
    with railcontact.Client(target, tls=ca, timeout_s=60) as c:
        with pytest.raises(railcontact.RailcontactError) as e:
            c.solve_patch(rolling_case("fastsim"))
        assert e.value.code == grpc.StatusCode.UNAUTHENTICATED
    with railcontact.Client(target, tls=ca, token=SOLVE_TOKEN, timeout_s=60) as c:
        with pytest.raises(railcontact.RailcontactError) as e:
            c.register_pair(builtin="mbench_s1002_uic60")
        assert e.value.code == grpc.StatusCode.PERMISSION_DENIED
        assert "admin" in e.value.message
    with railcontact.Client(target, tls=ca, token=ADMIN_TOKEN, timeout_s=120) as c:
        assert c.register_pair(builtin="mbench_s1002_uic60").pair_id


def test_plaintext_client_gets_nothing_from_a_tls_server(secure):
    target, _ = secure
    with railcontact.Client(target, token=SOLVE_TOKEN, timeout_s=5) as c:
        with pytest.raises(railcontact.RailcontactError) as e:
            c.solve_patch(rolling_case("fastsim"))
        assert e.value.code == grpc.StatusCode.UNAVAILABLE
