"""The bus's secret and the message codes of DTRON's NATS bus (the site's page "Security: the bus's secret").

Every member holds the bus's secret (by default the key file ``~/.dtron/bus.key``, or ``$DTRON_HOME/bus.key``,
made by the first member that needs it) and signs every message it publishes with headers ``Dtron-Seq``,
``Dtron-Time`` and ``Dtron-Mac``; every member checks every message it reads before anything else, and drops one
that is unauthenticated, replayed or stale.
"""

from __future__ import annotations

import errno
import hashlib
import hmac
import os
import secrets
import stat
import struct
import time
from pathlib import Path
from typing import Mapping, Optional, Union

#: The headers a member adds to every message it publishes.
SENDER, SEQ, TIME, MAC, PRESENCE, JOINED = ("Dtron-Sender", "Dtron-Seq", "Dtron-Time", "Dtron-Mac",
                                            "Dtron-Presence", "Dtron-Joined")
#: The reasons a message is dropped, as every DTRON member counts them.
UNAUTHENTICATED, REPLAYED, STALE = "UNAUTHENTICATED", "REPLAYED", "STALE"
#: How many numbers below a sender's highest are remembered; anything lower is replayed.
REPLAY_WINDOW = 4096
#: The most a message's Dtron-Time may be away from when the stream stored it.
STALE_NS = 120_000_000_000
#: A sender accepted nothing for this long (by the stream's clock) is forgotten: any message of it replayed now
#: would be stale, since its Dtron-Time lies more than STALE_NS before the stream's time.
FORGET_NS = 2 * STALE_NS

_KEY_LABEL = b"dtron-bus-mac-v1"
_MAX_KEY_FILE = 64 * 1024

PathLike = Union[str, "os.PathLike[str]"]


class KeyFileError(ValueError):
    """A key file that cannot be used: missing (when named), empty, or open to group or others."""


def default_key_file() -> Path:
    """``$DTRON_HOME/bus.key`` when ``DTRON_HOME`` is set, else ``~/.dtron/bus.key``."""
    home = os.environ.get("DTRON_HOME")
    return (Path(home) if home else Path.home() / ".dtron") / "bus.key"


def load_secret(key_file: Optional[PathLike] = None) -> bytes:
    """The secret in ``key_file``; without one, in :func:`default_key_file`, which is made if there is none.

    :raises KeyFileError: if the file is missing (a named one is never made), empty, not a regular file, or group
        or others may read or write it
    """
    if key_file is not None:
        return _read(Path(key_file))
    path = default_key_file()
    if not path.exists():
        _create(path)
    return _read(path)


def _read(path: Path) -> bytes:
    try:
        fd = os.open(path, os.O_RDONLY | getattr(os, "O_CLOEXEC", 0))
    except FileNotFoundError:
        raise KeyFileError(f"key file {path} does not exist") from None
    except OSError as e:
        raise KeyFileError(f"key file {path} cannot be read: {e.strerror}") from None
    try:
        info = os.fstat(fd)
        if not stat.S_ISREG(info.st_mode):
            raise KeyFileError(f"key file {path} is not a regular file")
        if info.st_mode & 0o066:
            raise KeyFileError(f"key file {path} may be read or written by group or others "
                               f"(mode {info.st_mode & 0o777:o}): chmod 600 {path}")
        content = os.read(fd, _MAX_KEY_FILE + 1)
    finally:
        os.close(fd)
    if len(content) > _MAX_KEY_FILE:
        raise KeyFileError(f"key file {path} is longer than {_MAX_KEY_FILE} bytes")
    try:
        secret = content.decode("utf-8").strip().encode("utf-8")
    except UnicodeDecodeError:
        raise KeyFileError(f"key file {path} is not UTF-8 text") from None
    if not secret:
        raise KeyFileError(f"key file {path} is empty")
    return secret


def _create(path: Path) -> None:
    """Makes the default key file: the folder with mode 0700, a temporary file with mode 0600 holding 64 random
    hexadecimal digits, linked to the final name; if another member linked one first, that one stays."""
    try:
        os.makedirs(path.parent, mode=0o700, exist_ok=True)
    except OSError as e:
        raise KeyFileError(f"cannot make the folder of key file {path}: {e.strerror}") from None
    temporary = path.parent / f".bus.key.{os.getpid()}.{secrets.token_hex(8)}"
    try:
        fd = os.open(temporary, os.O_WRONLY | os.O_CREAT | os.O_EXCL | getattr(os, "O_CLOEXEC", 0), 0o600)
    except OSError as e:
        raise KeyFileError(f"cannot make key file {path}: {e.strerror}") from None
    try:
        try:
            os.fchmod(fd, 0o600)  # whatever the umask
            os.write(fd, (secrets.token_hex(32) + "\n").encode("ascii"))
            os.fsync(fd)
        finally:
            os.close(fd)
        try:
            os.link(temporary, path)
        except OSError as e:
            if e.errno != errno.EEXIST:  # another member made it first: use that one
                raise KeyFileError(f"cannot make key file {path}: {e.strerror}") from None
    except OSError as e:
        raise KeyFileError(f"cannot make key file {path}: {e.strerror}") from None
    finally:
        try:
            os.unlink(temporary)
        except OSError:
            pass


def mac_key(secret: bytes) -> bytes:
    """``K = HMAC-SHA256(secret, "dtron-bus-mac-v1")``, the key of every message code."""
    return hmac.new(secret, _KEY_LABEL, hashlib.sha256).digest()


def message_input(subject: str, headers: Mapping[str, str], data: bytes) -> bytes:
    """``M``: subject, Dtron-Sender, Dtron-Seq, Dtron-Time, Dtron-Presence, Dtron-Joined (absent ones empty) and the
    data, each as its length in bytes (unsigned 32-bit big-endian) followed by its bytes (strings in UTF-8)."""
    items = [subject.encode("utf-8")]
    items += [headers.get(name, "").encode("utf-8") for name in (SENDER, SEQ, TIME, PRESENCE, JOINED)]
    items.append(bytes(data))
    return b"".join(struct.pack(">I", len(item)) + item for item in items)


def message_code(key: bytes, subject: str, headers: Mapping[str, str], data: bytes) -> str:
    """``Dtron-Mac``: ``HMAC-SHA256(K, M)`` in 64 lowercase hexadecimal digits."""
    return hmac.new(key, message_input(subject, headers, data), hashlib.sha256).hexdigest()


class _Window:
    """The numbers accepted from one sender: the highest, and which of the REPLAY_WINDOW below it (a bit mask)."""

    __slots__ = ("highest", "seen", "last_ns")

    def __init__(self) -> None:
        self.highest = 0
        self.seen = 0  # bit i: highest - i was accepted
        self.last_ns = 0

    def fresh(self, number: int) -> bool:
        if number > self.highest:
            return True
        behind = self.highest - number
        return behind < REPLAY_WINDOW and not (self.seen >> behind) & 1

    def accept(self, number: int, stream_ns: int) -> None:
        if number > self.highest:
            shift = number - self.highest
            self.seen = ((self.seen << shift) | 1) & ((1 << REPLAY_WINDOW) - 1) if shift < REPLAY_WINDOW else 1
            self.highest = number
        else:
            self.seen |= 1 << (self.highest - number)
        self.last_ns = max(self.last_ns, stream_ns)


class Guard:
    """Signs the messages one member publishes and checks the ones it reads."""

    def __init__(self, secret: bytes, first_number: Optional[int] = None) -> None:
        """``first_number``: of this member's first message, by default the wall clock now in nanoseconds, so that
        a member started again under the same id goes on above the numbers it used before."""
        self._key = mac_key(secret)
        self._sequence = (time.time_ns() if first_number is None else first_number) - 1
        self._windows: dict[str, _Window] = {}
        self._forget_at = 0

    def sign(self, subject: str, headers: Mapping[str, str], data: bytes, now_ns: int) -> dict[str, str]:
        """The headers with this member's next Dtron-Seq, Dtron-Time ``now_ns`` and the code; a message published
        again after a failed attempt is published with the same headers."""
        self._sequence += 1
        signed = dict(headers)
        signed[SEQ] = str(self._sequence)
        signed[TIME] = str(now_ns)
        signed[MAC] = message_code(self._key, subject, signed, data)
        return signed

    @property
    def next_number(self) -> int:
        """The Dtron-Seq of the next message this member signs."""
        return self._sequence + 1

    def _authentic(self, subject: str, headers: Mapping[str, str], data: bytes) -> bool:
        code = headers.get(MAC)
        return code is not None and hmac.compare_digest(code.encode("utf-8", "replace"),
                                                        message_code(self._key, subject, headers, data).encode("ascii"))

    def learn(self, subject: str, headers: Mapping[str, str], data: bytes, stream_ns: int) -> bool:
        """Takes note of the number of a message published before this member joined, so that a copy of it published
        again later is replayed: only a message whose code is valid counts, whatever its time. True if it counted."""
        number = _decimal(headers.get(SEQ))
        if number is None or number < 1 or not self._authentic(subject, headers, data):
            return False
        window = self._windows.setdefault(headers.get(SENDER, ""), _Window())
        if window.fresh(number):
            window.accept(number, stream_ns)
        return True

    def check(self, subject: str, headers: Mapping[str, str], data: bytes, stream_ns: int) -> Optional[str]:
        """None if the message is authentic, new and fresh (its number is then remembered), else why it is dropped:
        UNAUTHENTICATED, REPLAYED or STALE. ``stream_ns`` is when the stream stored it."""
        if not self._authentic(subject, headers, data):
            return UNAUTHENTICATED
        number = _decimal(headers.get(SEQ))
        sender = headers.get(SENDER, "")
        window = self._windows.get(sender)
        if number is None or number < 1 or (window is not None and not window.fresh(number)):
            return REPLAYED
        sent = _decimal(headers.get(TIME))
        if sent is None or abs(sent - stream_ns) > STALE_NS:
            return STALE
        if window is None:
            self._forget(stream_ns)
            window = self._windows[sender] = _Window()
        window.accept(number, stream_ns)
        return None

    def _forget(self, stream_ns: int) -> None:
        """Forgets the senders that accepted nothing for FORGET_NS (checked at most every STALE_NS)."""
        if stream_ns < self._forget_at:
            return
        self._forget_at = stream_ns + STALE_NS
        for sender in [s for s, w in self._windows.items() if w.last_ns < stream_ns - FORGET_NS]:
            del self._windows[sender]


def _decimal(text: Optional[str]) -> Optional[int]:
    """A decimal number below 2**63, else None."""
    if text is None or not 0 < len(text) <= 19 or not text.isascii() or not text.isdigit():
        return None
    value = int(text)
    return value if value < 2**63 else None
