"""A nats-server with JetStream on a free loopback port and a store in a temporary folder, for the tests that need
one: skipped when nats-server is not installed, unless DTRON_REQUIRE_NATS=1 (as in CI) makes that a failure. Every
test has a DTRON_HOME of its own (so the bus's key file is made there, never in ~/.dtron), and a signer of messages
made apart from the client's, after the page "Security: the bus's secret"."""

from __future__ import annotations

import hashlib
import hmac
import os
import shutil
import socket
import subprocess
import time
from pathlib import Path
from typing import Iterator, Optional

import pytest


def _nats_server() -> str | None:
    return shutil.which("nats-server") or (
        "/usr/sbin/nats-server" if os.access("/usr/sbin/nats-server", os.X_OK) else None)


def free_port() -> int:
    with socket.socket() as s:
        s.bind(("127.0.0.1", 0))
        return s.getsockname()[1]


@pytest.fixture(autouse=True)
def dtron_home(tmp_path: Path, monkeypatch: pytest.MonkeyPatch) -> Path:
    """DTRON_HOME in the test's temporary folder (not made yet: the first member makes it)."""
    home = tmp_path / "dtron-home"
    monkeypatch.setenv("DTRON_HOME", str(home))
    return home


class Signer:
    """Makes the headers of a member holding ``secret``: Dtron-Sender, Dtron-Seq, Dtron-Time and Dtron-Mac, with
    ``M`` built here from the page, not by the client's code."""

    def __init__(self, secret: bytes, sender: str) -> None:
        self.key = hmac.new(secret, b"dtron-bus-mac-v1", hashlib.sha256).digest()
        self.sender = sender
        self.seq = 0

    def headers(self, subject: str, data: bytes, presence: Optional[str] = None, joined: Optional[str] = None,
                time_ns: Optional[int] = None, seq: Optional[int] = None) -> dict[str, str]:
        if seq is None:
            self.seq += 1
            seq = self.seq
        headers = {"Dtron-Sender": self.sender, "Dtron-Seq": str(seq),
                   "Dtron-Time": str(time.time_ns() if time_ns is None else time_ns)}
        if presence is not None:
            headers["Dtron-Presence"] = presence
        if joined is not None:
            headers["Dtron-Joined"] = joined
        items = [subject, self.sender, headers["Dtron-Seq"], headers["Dtron-Time"], presence or "", joined or ""]
        m = b"".join(len(b).to_bytes(4, "big") + b for b in [i.encode() for i in items] + [data])
        headers["Dtron-Mac"] = hmac.new(self.key, m, hashlib.sha256).hexdigest()
        return headers


def bus_secret(home: Path) -> bytes:
    """The secret of the key file the members made in ``home``."""
    return (home / "bus.key").read_text().strip().encode()


@pytest.fixture
def nats_url(tmp_path: Path) -> Iterator[str]:
    yield from _serve(tmp_path, [])


@pytest.fixture
def nats_url_with_user(tmp_path: Path) -> Iterator[str]:
    """A server that takes only user "lab" with password "s3cret"."""
    yield from _serve(tmp_path, ["--user", "lab", "--pass", "s3cret"])


@pytest.fixture
def nats_url_with_token(tmp_path: Path) -> Iterator[str]:
    """A server that takes only clients with the token "t0ken-s3cret"."""
    yield from _serve(tmp_path, ["--auth", "t0ken-s3cret"])


@pytest.fixture
def nats_tls(tmp_path: Path) -> Iterator[tuple[str, Path, Path]]:
    """A server that talks TLS only, with a certificate for 127.0.0.1 signed by a test authority: its tls:// URL,
    the authority's PEM file, and the PEM file of another authority that did not sign it."""
    for name in ("ca", "other-ca"):
        _openssl(tmp_path, "req", "-x509", "-newkey", "rsa:2048", "-nodes", "-keyout", f"{name}.key", "-out",
                 f"{name}.pem", "-days", "1", "-subj", f"/CN=dtron-test-{name}")
    _openssl(tmp_path, "req", "-newkey", "rsa:2048", "-nodes", "-keyout", "server.key", "-out", "server.csr",
             "-subj", "/CN=127.0.0.1")
    (tmp_path / "san.cnf").write_text("subjectAltName=IP:127.0.0.1\n")
    _openssl(tmp_path, "x509", "-req", "-in", "server.csr", "-CA", "ca.pem", "-CAkey", "ca.key", "-CAcreateserial",
             "-out", "server.pem", "-days", "1", "-extfile", "san.cnf")
    for url in _serve(tmp_path, ["--tls", "--tlscert", str(tmp_path / "server.pem"), "--tlskey",
                                 str(tmp_path / "server.key")]):
        yield url.replace("nats://", "tls://"), tmp_path / "ca.pem", tmp_path / "other-ca.pem"


def _openssl(folder: Path, *args: str) -> None:
    if shutil.which("openssl") is None:
        if os.environ.get("DTRON_REQUIRE_NATS") == "1":
            pytest.fail("openssl is missing, and DTRON_REQUIRE_NATS=1 requires it")
        pytest.skip("openssl is not installed: skipped (CI installs it)")
    done = subprocess.run(["openssl", *args], cwd=folder, capture_output=True, text=True, timeout=60)
    if done.returncode != 0:
        pytest.fail(f"openssl {' '.join(args)}:\n{done.stderr}")


def _serve(tmp_path: Path, options: list[str]) -> Iterator[str]:
    binary = _nats_server()
    if binary is None:
        if os.environ.get("DTRON_REQUIRE_NATS") == "1":
            pytest.fail("nats-server is missing, and DTRON_REQUIRE_NATS=1 requires it")
        pytest.skip("nats-server is not installed: skipped (CI installs it)")
    port = free_port()
    log = tmp_path / "nats.log"
    with open(log, "w") as out:
        server = subprocess.Popen([binary, "-a", "127.0.0.1", "-p", str(port), "-js", "-sd", str(tmp_path / "js"),
                                   *options], stdout=out, stderr=subprocess.STDOUT)
    try:
        deadline = time.monotonic() + 30
        while "Server is ready" not in log.read_text():
            if server.poll() is not None or time.monotonic() > deadline:
                pytest.fail("nats-server did not start:\n" + log.read_text())
            time.sleep(0.02)
        yield f"nats://127.0.0.1:{port}"
    finally:
        server.terminate()
        server.wait(10)
