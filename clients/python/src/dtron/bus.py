"""A member of a DTRON bus on NATS JetStream, speaking the same protocol as DTRON's Java API.

The bus is one JetStream stream per bus name (``DTRON_<bus>``, subjects ``dtron.<bus>.>``): every member publishes
into it and delivers it from an ordered consumer, so that all members, in any language, see one order. A channel
message travels on ``dtron.<bus>.c.<channel>`` as a protobuf ``Sync`` with header ``Dtron-Sender``; presence (join,
alive every second, leave) travels on ``dtron.<bus>.p``, so that the tester sees this member join and notices when
it is gone. Every message carries a code made with the bus's secret (:mod:`dtron.secret`), and every message read is
checked before anything else: one without a valid code, a replayed or a stale one is dropped and counted.
"""

from __future__ import annotations

import asyncio
import datetime
import inspect
import logging
import secrets
import os
import re
import ssl
from dataclasses import dataclass, field, replace
from typing import Any, Awaitable, Callable, Optional, Sequence, Union

import nats
from nats.js import api
from nats.js.errors import APIError, NotFoundError

from dtron._proto import Sync_pb2
from dtron.channel import RESERVED, Channel, InvalidMessage, Message
from dtron.clock import SAME_CLOCK_SLACK_NS, ClockOffset, OffsetEstimator, RunClock, host_clock_id, same_clock, wall_clock_ns
from dtron.secret import MAC, SEQ, UNAUTHENTICATED, Guard, PathLike, load_secret

LOG = logging.getLogger("dtron")

#: The channel on which the tester starts a run (variable ``timeunit``: microseconds per model time unit).
RUN_START = Channel("dtron_start", "timeunit")
#: The channel on which the tester ends a run.
RUN_STOP = Channel("dtron_stop")

HEARTBEAT_S = 1.0
SILENCE_NS = 4_000_000_000
MAX_AGE_S = 600.0
MAX_BYTES = 64 * 1024 * 1024
DUPLICATE_WINDOW_S = 60.0
PING_BURST = 8
PING_SPACING_S = 0.02
PING_PERIOD_S = 1.0
RETRY_FOR_S = 30.0
JOIN_WAIT_S = 10.0
#: How far back a member joining a secure bus reads the stream, before the stream's last message (security.md).
HISTORY_S = 240.0
_BUS_NAME = re.compile(r"[A-Za-z0-9_-]{1,64}\Z")
_MEMBER_NAME = re.compile(r"[\x21-\x7e]{1,128}\Z")
_CONTROL = frozenset({"dtron_hello", "dtron_ping", "dtron_pong", "dtron_serve"})
_NAMED_DROPS = 1024
_PRINTABLE = 128

Listener = Callable[[Message], Union[None, Awaitable[None]]]


@dataclass
class Stats:
    """This member's counters: published messages, accepted and rejected ones by reason, listener failures.

    Reasons: UNAUTHENTICATED, REPLAYED and STALE for messages dropped by the bus's secret (:mod:`dtron.secret`);
    MALFORMED, UNKNOWN_CHANNEL, UNKNOWN_VARIABLES and MISSING_VARIABLES for ones that do not fit their channel.
    """

    published: int = 0
    accepted: int = 0
    rejected: dict[str, int] = field(default_factory=dict)
    listener_failures: int = 0

    @property
    def rejected_total(self) -> int:
        """All rejected messages."""
        return sum(self.rejected.values())


@dataclass
class _Registration:
    channel: Channel
    listeners: list[tuple[Listener, bool]]


class Bus:
    """One member of a DTRON bus. Create it with :func:`connect`; use it as an async context manager or close it.

    Listeners are called one at a time in the bus's order, with the messages of their channel; an input of the
    current run's tester is acknowledged when its listeners returned (unless a listener was added with
    ``auto_ack=False``: then call :meth:`acknowledge`).
    """

    def __init__(self, nc: Any, js: Any, bus: str, member: str, guard: Optional[Guard]) -> None:
        self._nc = nc
        self._guard = guard
        self._named_drops: set[tuple[str, str]] = set()
        self._js = js
        self.bus = bus
        #: This member's id on the bus.
        self.member = member
        self._prefix = f"dtron.{bus}.c."
        self._presence_subject = f"dtron.{bus}.p"
        self.stats = Stats()
        self._registrations: dict[str, _Registration] = {}
        self._sends: set[str] = set()
        self._sequence = 0
        self._outbox: asyncio.Queue[Optional[tuple[str, dict[str, str], bytes, Optional[asyncio.Future[None]]]]] = \
            asyncio.Queue()
        self._inbox: asyncio.Queue[Optional[Callable[[], Awaitable[None]]]] = asyncio.Queue()
        self._members: list[str] = [member]
        self._last_seen: dict[str, float] = {}
        self._joined_at: dict[str, int] = {}
        self._own_join = 0
        self._joined = asyncio.Event()
        # on a secure bus, until this member's join came back: the Dtron-Seq of the join; the stream's messages
        # before it are read only for their senders' numbers (security.md)
        self._learning_until: Optional[str] = None
        self._last_read = 0.0
        self._tester: Optional[str] = None
        self._run_tester: Optional[str] = None
        self._run_id = ""
        self._estimator = OffsetEstimator()
        self._estimate: Optional[ClockOffset] = None
        # the tester said it reads this member's very clock, and no round trip contradicted it (then offset 0)
        self._host_clock = host_clock_id()
        self._same_clock_refuted = False
        self._pending_pings: dict[int, int] = {}
        self._pinging: Optional[asyncio.Task[None]] = None
        self._acked: dict[tuple[str, int], None] = {}
        self._closed = False
        self.run_clock = RunClock(wall_clock_ns, lambda: self._estimate.offset_ns if self._estimate else 0)
        self._sub: Any = None
        self._tasks: list[asyncio.Task[None]] = []
        self._heartbeats: Optional[asyncio.Task[None]] = None

    # -- public API -----------------------------------------------------------------------------------------------

    @property
    def members(self) -> list[str]:
        """The members on the bus now, oldest first."""
        return list(self._members)

    @property
    def tester(self) -> Optional[str]:
        """The tester this member knows (from its hello or the run's start), if any."""
        return self._tester

    @property
    def clock_offset(self) -> Optional[ClockOffset]:
        """The estimate of (tester's clock - own clock) with its error bound, once a ping came back."""
        return self._estimate

    @property
    def run_id(self) -> str:
        """The current run's id, or ""."""
        return self._run_id

    def add_listener(self, channel: Channel, callback: Listener, auto_ack: bool = True) -> None:
        """Calls ``callback`` (a function or a coroutine function) with every message on ``channel`` from now on.

        :raises ValueError: if the channel is one only DTRON sends on, or has another template here already
        """
        if channel.name in _CONTROL or channel.name == "dtron_ack":
            raise ValueError(f"channel {channel.name!r} is DTRON's own; no listener can be added")
        registration = self._registrations.get(channel.name)
        if registration is None:
            registration = self._registrations.setdefault(channel.name, _Registration(channel, []))
        elif registration.channel != channel:
            raise ValueError(f"listener template {channel} differs from {registration.channel}")
        registration.listeners.append((callback, auto_ack))
        if channel.name not in RESERVED:
            self._announce()

    def listener(self, channel: Channel, auto_ack: bool = True) -> Callable[[Listener], Listener]:
        """Decorator form of :meth:`add_listener`."""

        def register(callback: Listener) -> Listener:
            self.add_listener(channel, callback, auto_ack)
            return callback

        return register

    def declare_outputs(self, *channels: Channel) -> None:
        """Says which channels this member sends (a tester's outputs), so a tester waiting for them knows."""
        names = {c.name for c in channels}
        if names & RESERVED:
            raise ValueError(f"channels {sorted(names & RESERVED)} are DTRON's own")
        if not names <= self._sends:
            self._sends |= names
            self._announce()

    async def send(self, message: Message, event_time_ns: Optional[int] = None) -> Message:
        """Publishes a message to every member; ``event_time_ns`` (own wall clock) is when its event happened.

        Returns once the message is queued for the bus, in order, without waiting for the stream's
        acknowledgement (a message the bus refuses is logged), so a slow server does not hold up the caller.

        :returns: the message as published, with sender, sequence number and times
        :raises ValueError: if the channel is one only DTRON sends on
        :raises RuntimeError: if this member is closed
        """
        if self._closed:
            raise RuntimeError("closed")
        if message.name in _CONTROL or message.name == "dtron_ack":
            raise ValueError(f"only DTRON publishes on channel {message.name!r}")
        message.channel.check(frozenset(message.variables))
        if message.name not in RESERVED and message.name not in self._sends:
            self._sends.add(message.name)
            self._announce()
        now = wall_clock_ns()
        stamped = self._stamp(message, now, event_time_ns or now)
        await self._put(message.name, self._encode(stamped), wait=False)
        self.stats.published += 1
        return stamped

    async def acknowledge(self, message: Message, applied_at_ns: Optional[int] = None) -> bool:
        """Acknowledges an input: publishes on ``dtron_ack`` that this member applied it at ``applied_at_ns``.

        :returns: False if this member had acknowledged the message before
        """
        if not message.sender or message.sequence <= 0:
            raise ValueError("only a message received from the bus can be acknowledged")
        key = (message.sender, message.sequence)
        if key in self._acked:
            return False
        self._acked[key] = None
        if len(self._acked) > 65536:
            self._acked.pop(next(iter(self._acked)))
        now = wall_clock_ns()
        ack = self._stamp(Message(Channel("dtron_ack")), now, applied_at_ns or now)
        await self._put("dtron_ack", self._encode(ack, acked=(message.sender, message.sequence)), wait=False)
        return True

    async def close(self) -> None:
        """Says leave and leaves the bus; closing twice does nothing."""
        if self._closed:
            return
        self._closed = True
        for task in (self._pinging, self._heartbeats):
            if task is not None:
                task.cancel()
        self.run_clock.stop()
        try:
            # queued after this member's last messages, so that none comes after its leave
            await asyncio.wait_for(self._put_presence("leave", wait=True), timeout=3.0)
        except Exception as e:  # the bus may be gone already
            LOG.debug("%s cannot say leave: %s", self.member, e)
        await self._outbox.put(None)
        await self._inbox.put(None)
        for task in self._tasks:
            try:
                await asyncio.wait_for(task, timeout=5)
            except (asyncio.TimeoutError, asyncio.CancelledError):
                task.cancel()
        if self._sub is not None:
            try:
                await self._sub.unsubscribe()
            except Exception as e:
                LOG.debug("%s cannot unsubscribe: %s", self.member, e)
        await self._nc.close()

    async def __aenter__(self) -> "Bus":
        return self

    async def __aexit__(self, *exc: object) -> None:
        await self.close()

    # -- sending --------------------------------------------------------------------------------------------------

    def _stamp(self, message: Message, publish_ns: int, event_ns: int) -> Message:
        self._sequence += 1
        estimate = self._estimate
        return replace(message, sender=self.member, sequence=self._sequence, publish_time_ns=publish_ns,
                       event_time_ns=event_ns, run_id=self._run_id,
                       clock_offset_ns=estimate.offset_ns if estimate else 0,
                       clock_error_ns=estimate.error_ns if estimate else 0)

    @staticmethod
    def _encode(message: Message, acked: tuple[str, int] = ("", 0), receives: Sequence[str] = (),
                sends: Sequence[str] = ()) -> bytes:
        sync = Sync_pb2.Sync(name=message.name, sender=message.sender, sequence=message.sequence,
                             publish_time_ns=message.publish_time_ns, run_id=message.run_id,
                             acked_sender=acked[0], acked_sequence=acked[1],
                             clock_offset_ns=message.clock_offset_ns, clock_error_ns=message.clock_error_ns,
                             receives=list(receives), sends=list(sends))
        if message.event_time_ns != message.publish_time_ns:
            sync.event_time_ns = message.event_time_ns
        for name, value in message.variables.items():
            sync.variables.add(name=name, value=value)
        return sync.SerializeToString()

    async def _put(self, channel: str, payload: bytes, wait: bool) -> None:
        await self._enqueue(self._prefix + channel, {"Dtron-Sender": self.member}, payload, wait)

    async def _put_presence(self, what: str, wait: bool = False) -> None:
        headers = {"Dtron-Sender": self.member, "Dtron-Presence": what}
        if what == "alive" and self._own_join:
            headers["Dtron-Joined"] = str(self._own_join)
        await self._enqueue(self._presence_subject, headers, b"", wait)

    async def _enqueue(self, subject: str, headers: dict[str, str], payload: bytes, wait: bool) -> None:
        future: Optional[asyncio.Future[None]] = asyncio.get_running_loop().create_future() if wait else None
        await self._outbox.put((subject, headers, payload, future))
        if future is not None:
            await future

    async def _publish(self, subject: str, headers: dict[str, str], payload: bytes) -> None:
        """Publishes into the stream until it acknowledged the message: a message that fails while a server fails
        over is published again with the same ``Nats-Msg-Id``, so that the stream stores it once."""
        # an id no one can tell in advance: no other process can publish first under it and have the stream drop
        # this message as the duplicate
        headers = dict(headers, **{"Nats-Msg-Id": f"{self.member}-{secrets.token_hex(16)}"})
        if self._guard is not None:  # signed once: a message published again keeps its number, time and code
            headers = self._guard.sign(subject, headers, payload, wall_clock_ns())
        loop = asyncio.get_running_loop()
        deadline = loop.time() + RETRY_FOR_S
        while True:
            try:
                await self._js.publish(subject, payload, headers=headers, timeout=2.0)
                return
            except APIError as e:
                if e.code != 503:  # refused for good (limits, a bad subject)
                    raise
                failure: Exception = e
            except Exception as e:  # a timeout, no responders, a connection being re-established
                failure = e
            if self._nc.is_closed or loop.time() > deadline:
                raise ConnectionError(f"not stored within {RETRY_FOR_S} s: {failure}")
            await asyncio.sleep(0.1)

    async def _publisher(self) -> None:
        """Publishes the queued messages one after the other, in the order they were stamped."""
        while True:
            item = await self._outbox.get()
            if item is None:
                return
            subject, headers, payload, future = item
            try:
                await self._publish(subject, headers, payload)
                if future is not None and not future.done():
                    future.set_result(None)
            except Exception as e:
                LOG.warning("%s: a message on %s was dropped: %s", self.member, subject, e)
                if future is not None and not future.done():
                    future.set_exception(ConnectionError(f"cannot publish on {subject}: {e}"))

    def _control(self, channel: str, event_ns: Optional[int] = None, acked: tuple[str, int] = ("", 0)) -> None:
        """Queues a control message (hello, ping, pong, serve) without waiting for it."""
        now = wall_clock_ns()
        message = self._stamp(Message(Channel(channel)), now, event_ns or now)
        if channel == "dtron_ping":
            self._pending_pings[message.sequence] = now
            while len(self._pending_pings) > 64:
                self._pending_pings.pop(next(iter(self._pending_pings)))
        receives: list[str] = []
        sends: list[str] = []
        if channel == "dtron_serve":
            receives = sorted(n for n in self._registrations if n not in RESERVED)
            sends = sorted(self._sends)
        payload = self._encode(message, acked, receives, sends)
        self._outbox.put_nowait((self._prefix + channel, {"Dtron-Sender": self.member}, payload, None))

    def _announce(self) -> None:
        if not self._closed:
            self._control("dtron_serve")

    async def _heartbeat(self) -> None:
        while not self._closed:
            await asyncio.sleep(HEARTBEAT_S)
            if not self._closed:
                await self._put_presence("alive")

    async def _ping(self, tester: str) -> None:
        count = 0
        while not self._closed and self._tester == tester:
            self._control("dtron_ping")
            count += 1
            await asyncio.sleep(PING_SPACING_S if count < PING_BURST else PING_PERIOD_S)

    # -- receiving ------------------------------------------------------------------------------------------------

    async def _dispatcher(self) -> None:
        while True:
            job = await self._inbox.get()
            if job is None:
                return
            await job()

    async def _received(self, msg: Any) -> None:
        """The ordered consumer's callback: one stream message at a time, in stream order."""
        received_ns = wall_clock_ns()
        if self._closed:
            return
        headers = msg.headers or {}
        sender = headers.get("Dtron-Sender")
        presence = msg.subject == self._presence_subject
        try:
            meta = msg.metadata
            stream_ns = int(meta.timestamp.timestamp() * 1e9)
        except Exception as e:
            LOG.warning("a message on %s without its stream's metadata was dropped: %s", msg.subject, e)
            return
        self._last_read = asyncio.get_running_loop().time()
        until = self._learning_until
        own_join = until is not None and (sender, headers.get(SEQ)) == (self.member, until)
        if self._guard is not None and until is not None and not own_join:
            self._guard.learn(msg.subject, headers, msg.data, stream_ns)  # published before this member joined
            return
        if self._guard is not None:
            dropped = self._guard.check(msg.subject, headers, msg.data, stream_ns)
            if own_join and dropped != UNAUTHENTICATED:
                self._learning_until = None
        else:  # an insecure member does not read a secure one's messages, which it cannot check
            dropped = UNAUTHENTICATED if MAC in headers else None
        if dropped is not None:
            self._drop(msg.subject, sender or "", dropped)
            return
        try:
            self._membership(meta.sequence.stream, stream_ns, sender, headers if presence else None)
        except Exception as e:
            LOG.warning("membership update failed: %s", e)
        if presence or not msg.subject.startswith(self._prefix):
            return
        self._message(msg.subject[len(self._prefix):], msg.data, sender or "", received_ns)

    def _drop(self, subject: str, sender: str, reason: str) -> None:
        """Counts a message the bus's secret drops, and names the first of each sender and reason in the log."""
        self.stats.rejected[reason] = self.stats.rejected.get(reason, 0) + 1
        sender = _printable(sender)
        if (sender, reason) not in self._named_drops and len(self._named_drops) < _NAMED_DROPS:
            self._named_drops.add((sender, reason))
            why = ("it carries a message code, and this member is insecure" if self._guard is None
                   else {"UNAUTHENTICATED": "no valid code of the bus's secret",
                         "REPLAYED": "its Dtron-Seq was accepted before", "STALE": "its Dtron-Time is more than "
                         "120 s away from when the stream stored it"}.get(reason, reason))
            LOG.warning("%s dropped a message on %s from %r, %s: %s (further ones are counted only)", self.member,
                        _printable(subject), sender, reason, why)

    def _membership(self, sequence: int, stream_ns: float, sender: Optional[str],
                    presence: Optional[dict[str, str]]) -> None:
        before = list(self._members)
        members = [m for m in before if not (m in self._last_seen and self._last_seen[m] < stream_ns - SILENCE_NS)]
        if sender is not None and (sender in members or presence is not None):
            self._last_seen[sender] = stream_ns
        if presence is not None and sender is not None:
            what = presence.get("Dtron-Presence", "")
            if what in ("join", "alive"):
                joined = sequence
                if what == "alive":
                    try:
                        joined = int(presence.get("Dtron-Joined", sequence))
                    except ValueError:
                        joined = sequence
                if sender not in members:
                    members.append(sender)
                    self._joined_at[sender] = joined
                elif what == "join":
                    self._joined_at[sender] = joined
                if what == "join" and sender == self.member:
                    self._own_join = sequence
                    self._joined.set()
                elif what == "join" and not self._closed:
                    self._outbox.put_nowait((self._presence_subject, {"Dtron-Sender": self.member,
                                             "Dtron-Presence": "alive", "Dtron-Joined": str(self._own_join)},
                                             b"", None))
            elif what == "leave":
                if sender in members:
                    members.remove(sender)
                self._last_seen.pop(sender, None)
        if self.member not in members and self.member in before and self._joined.is_set() and not self._closed:
            LOG.warning("%s was silent in the stream for too long; joining again", self.member)
            self._outbox.put_nowait((self._presence_subject, {"Dtron-Sender": self.member,
                                                              "Dtron-Presence": "join"}, b"", None))
        members.sort(key=lambda m: (self._joined_at.get(m, 2**63), m))
        for gone in set(self._last_seen) - set(members):
            del self._last_seen[gone]
        if members != before:
            self._members = members
            left = set(before) - set(members)
            if self._tester is not None and self._tester in left:
                LOG.info("the tester %s left the bus", self._tester)
                self._forget_tester()

    def _forget_tester(self) -> None:
        self._tester = None
        self._run_tester = None
        self._run_id = ""
        self._estimator.clear()
        self._same_clock_refuted = False
        self._estimate = None
        self._pending_pings.clear()
        self.run_clock.stop()

    def _learn_tester(self, tester: str) -> None:
        if tester == self._tester:
            return
        self._tester = tester
        self._estimator.clear()
        self._same_clock_refuted = False
        self._estimate = None
        self._pending_pings.clear()
        if self._pinging:
            self._pinging.cancel()
        self._pinging = asyncio.get_running_loop().create_task(self._ping(tester))

    def _reject(self, channel: str, sender: str, error: InvalidMessage) -> None:
        self.stats.rejected[error.reason] = self.stats.rejected.get(error.reason, 0) + 1
        LOG.warning("Rejected a message on channel %r from %s, %s", _printable(channel), _printable(sender), error)

    def _message(self, channel: str, data: bytes, transport_sender: str, received_ns: int) -> None:
        registration = self._registrations.get(channel)
        run_channel = channel in ("dtron_start", "dtron_stop")
        if registration is None and not run_channel and channel not in _CONTROL and channel != "dtron_ack":
            return  # not for this member (another member's channel, or a tester's verdict)
        try:
            sync = Sync_pb2.Sync.FromString(data)
        except Exception as e:
            self._reject(channel, transport_sender, InvalidMessage("MALFORMED", f"not a Sync message: {e}"))
            return
        if not sync.name:
            self._reject(channel, transport_sender, InvalidMessage("MALFORMED", "Sync message without a channel name"))
            return
        sender = sync.sender or transport_sender
        if channel in _CONTROL or channel == "dtron_ack":
            self._control_received(channel, sync, sender, received_ns)
            return
        template = registration.channel if registration else (RUN_START if channel == "dtron_start" else RUN_STOP)
        try:
            if sync.name != channel:
                raise InvalidMessage("UNKNOWN_CHANNEL", f"message names channel {sync.name!r}, expected {channel!r}")
            values: dict[str, int] = {}
            for variable in sync.variables:
                if not variable.name:
                    raise InvalidMessage("MALFORMED", f"variable without a name in channel {channel}")
                if variable.name in values:
                    raise InvalidMessage("MALFORMED", f"variable {variable.name} appears twice in channel {channel}")
                values[variable.name] = variable.value
            template.check(frozenset(values))
        except InvalidMessage as e:
            self._reject(channel, sender, e)
            return
        # a message of another run (one replayed from an earlier run, say) neither ends this run nor reaches the
        # listeners: a stop counts when it comes from this run's tester with this run's id (or none); a message with
        # a run id when it is this run's
        this_run = self._run_id != "" and sync.run_id == self._run_id
        if channel == "dtron_stop" and not ((this_run or not sync.run_id) and sender == self._run_tester):
            LOG.debug("Ignored a stop of run %r from %s: this run is %r", sync.run_id, sender, self._run_id)
            return
        if not run_channel and sync.run_id and not this_run:
            LOG.debug("Ignored a message on %r of run %r from %s: this run is %r", channel, sync.run_id, sender,
                      self._run_id)
            return
        message = Message(template, {v: values[v] for v in template.variables}, sender, sync.sequence,
                          sync.publish_time_ns, sync.event_time_ns or sync.publish_time_ns, sync.run_id,
                          sync.clock_offset_ns, sync.clock_error_ns, received_ns)
        if channel == "dtron_start":
            self._run_tester = sender
            self._run_id = sync.run_id
            if sender != self.member:
                self._learn_tester(sender)
            self.run_clock.start(message.event_time_ns, values.get("timeunit", 1000), sync.run_id)
        elif channel == "dtron_stop":
            self._run_tester = None
            self._run_id = ""
            self.run_clock.stop()
        if registration is None:
            return
        self.stats.accepted += 1
        acknowledge = (channel not in RESERVED and message.sequence > 0 and sender == self._run_tester
                       and sender != self.member)
        self._inbox.put_nowait(lambda: self._deliver(registration, message, acknowledge))

    def _control_received(self, channel: str, sync: Any, sender: str, received_ns: int) -> None:
        if sender == self.member:
            return
        if channel == "dtron_hello":
            if self._tester is None:
                self._learn_tester(sender)
            self._announce()
        elif channel == "dtron_ping":
            # the tester probes whether this member is there; a live monitor (field probe) asks it as well
            if sender == self._tester or sync.probe:
                self._control("dtron_pong", event_ns=received_ns, acked=(sender, sync.sequence))
        elif channel == "dtron_pong":
            if sync.acked_sender != self.member or sender != self._tester:
                return
            sent = self._pending_pings.pop(sync.acked_sequence, None)
            if sent is None:
                return
            tester_time = sync.event_time_ns or sync.publish_time_ns
            estimate = self._estimator.add(sent, tester_time, received_ns)
            within = same_clock(sent, tester_time, received_ns)
            self._same_clock_refuted |= not within
            if within and not self._same_clock_refuted and self._host_clock and sync.host_clock == self._host_clock:
                # the tester reads this very clock: offset 0, give or take its resolution
                estimate = (0, SAME_CLOCK_SLACK_NS)
            if estimate is not None:
                first = self._estimate is None
                self._estimate = ClockOffset(sender, estimate[0], estimate[1])
                if first:
                    LOG.info("Clock offset to the tester %s: %.3f ms +/- %.3f ms", sender, estimate[0] / 1e6,
                             estimate[1] / 1e6)

    async def _deliver(self, registration: _Registration, message: Message, acknowledge: bool) -> None:
        automatic = True
        called = False
        for callback, auto_ack in list(registration.listeners):
            called = True
            automatic &= auto_ack
            try:
                result = callback(message)
                if inspect.isawaitable(result):
                    await result
            except Exception:
                self.stats.listener_failures += 1
                LOG.exception("Listener %s failed on %s", callback, message)
        if acknowledge and called and automatic and not self._closed:
            try:
                await self.acknowledge(message, wall_clock_ns())
            except Exception as e:
                LOG.warning("%s cannot acknowledge %s: %s", self.member, message, e)


def generate_member_name() -> str:
    """A fresh member id: ``dtron-py-<pid>-<8 hex digits>``."""
    return f"dtron-py-{os.getpid()}-{secrets.token_hex(4)}"


async def connect(servers: Union[str, Sequence[str]] = "nats://127.0.0.1:4222", bus: str = "dtron",
                  member: Optional[str] = None, *, user: Optional[str] = None, password: Optional[str] = None,
                  token: Optional[str] = None, creds: Optional[str] = None, nkey_seed_file: Optional[str] = None,
                  tls_ca: Optional[str] = None, replicas: int = 1, key_file: Optional[PathLike] = None,
                  insecure: bool = False) -> Bus:
    """Joins a DTRON bus on NATS servers.

    Every member of a bus holds its secret: by default the key file ``~/.dtron/bus.key`` (``$DTRON_HOME/bus.key``
    when ``DTRON_HOME`` is set), which the first member on a machine makes; copy it to the other machines, or name
    a file with ``key_file``.

    :param servers: ``nats://HOST:PORT`` (or ``tls://``), one or a list, or comma-separated
    :param bus: the bus (the tester's ``--cluster``): stream ``DTRON_<bus>``
    :param member: this member's id, unique on the bus (default: generated)
    :param user: user name, with ``password``
    :param token: an authentication token
    :param creds: a NATS credentials file
    :param nkey_seed_file: a file with an nkey seed
    :param tls_ca: a PEM file of certificate authorities: TLS to the servers
    :param replicas: the stream's replicas if this member creates it
    :param key_file: the file with the bus's secret (never made; by default the one above, made if missing)
    :param insecure: neither sign nor check messages, for a bus with adapters of the original DTRON: anyone who
        reaches the NATS servers can then speak on the bus
    :raises ValueError: for a bad bus or member name
    :raises dtron.secret.KeyFileError: (a ValueError) for a key file that is missing, empty, or open to group or
        others, naming the file
    :raises ConnectionError: if the bus cannot be joined
    """
    if not _BUS_NAME.match(bus):
        raise ValueError(f"a NATS bus name is 1 to 64 letters, digits, '_' or '-': {bus!r}")
    member = member or generate_member_name()
    if not _MEMBER_NAME.match(member):
        raise ValueError(f"a member id is 1 to 128 printable characters without spaces: {member!r}")
    if insecure:
        if key_file is not None:
            raise ValueError("key_file and insecure=True exclude each other")
        LOG.warning("INSECURE: member %s on bus %r neither signs nor checks messages: anyone who can reach the NATS "
                    "servers can speak on this bus and change a verdict", member, bus)
        guard = None
    else:
        guard = Guard(load_secret(key_file))
    urls = [s.strip() for s in (servers.split(",") if isinstance(servers, str) else servers)]
    # a first connection fails after two tries of each server; once connected, reconnecting never stops (below)
    options: dict[str, Any] = {"servers": urls, "name": member, "max_reconnect_attempts": 2,
                               "reconnect_time_wait": 0.5, "allow_reconnect": True, "connect_timeout": 5}
    if user is not None:
        options.update(user=user, password=password)
    if token is not None:
        options["token"] = token
    if creds is not None:
        options["user_credentials"] = creds
    if nkey_seed_file is not None:
        options["nkeys_seed"] = nkey_seed_file
    if tls_ca is not None:
        options["tls"] = ssl.create_default_context(cafile=tls_ca)

    # nats-py reports a failed TLS handshake to error_cb and then never returns from connect: such an error ends
    # the first connection at once, and a deadline bounds it in any case
    tls_failed: asyncio.Future[Exception] = asyncio.get_running_loop().create_future()

    async def quiet(e: Exception) -> None:
        LOG.debug("NATS: %s", e)
        if isinstance(e, ssl.SSLError) and not tls_failed.done():
            tls_failed.set_result(e)

    options["error_cb"] = quiet
    connecting = asyncio.ensure_future(nats.connect(**options))
    deadline = len(urls) * 2 * (options["connect_timeout"] + options["reconnect_time_wait"]) + 5
    await asyncio.wait({connecting, tls_failed}, timeout=deadline, return_when=asyncio.FIRST_COMPLETED)
    if not connecting.done():
        connecting.cancel()
        reason = tls_failed.result() if tls_failed.done() else f"no connection within {deadline:g} s"
        raise ConnectionError(f"cannot connect to NATS servers {urls}: {reason}")
    tls_failed.cancel()
    try:
        nc = connecting.result()
    except Exception as e:
        raise ConnectionError(f"cannot connect to NATS servers {urls}: {e}") from e
    nc.options["max_reconnect_attempts"] = -1
    nc.options["reconnect_time_wait"] = 2
    try:
        js = nc.jetstream()
        stream = f"DTRON_{bus}"
        try:
            await js.stream_info(stream)
        except NotFoundError:
            config = api.StreamConfig(name=stream, subjects=[f"dtron.{bus}.>"], storage=api.StorageType.FILE,
                                      num_replicas=replicas, max_age=MAX_AGE_S, max_bytes=MAX_BYTES,
                                      discard=api.DiscardPolicy.OLD, duplicate_window=DUPLICATE_WINDOW_S)
            try:
                await js.add_stream(config)
            except Exception:
                await js.stream_info(stream)  # created by another member meanwhile
        member_bus = Bus(nc, js, bus, member, guard)
        loop = asyncio.get_running_loop()
        member_bus._tasks = [loop.create_task(member_bus._publisher()), loop.create_task(member_bus._dispatcher())]
        if guard is None:
            member_bus._sub = await js.subscribe(f"dtron.{bus}.>", cb=member_bus._received, ordered_consumer=True,
                                                 deliver_policy=api.DeliverPolicy.NEW)
        else:  # from HISTORY_S before the stream's last message, so that copies of those are known (security.md)
            member_bus._learning_until = str(guard.next_number)
            history = await _history(js, stream)
            member_bus._sub = await js.subscribe(f"dtron.{bus}.>", cb=member_bus._received, ordered_consumer=True,
                                                 config=history)
            # nats-py makes its ordered consumer anew (a server lost) from this very configuration and a start
            # sequence, which the server refuses together with a start time
            history.opt_start_time = None
        await member_bus._put_presence("join", wait=True)
        while not member_bus._joined.is_set():
            try:
                await asyncio.wait_for(member_bus._joined.wait(), timeout=JOIN_WAIT_S)
            except asyncio.TimeoutError:
                if member_bus._learning_until is None or loop.time() - member_bus._last_read > JOIN_WAIT_S:
                    raise  # else the messages before the join are still coming
        member_bus._heartbeats = loop.create_task(member_bus._heartbeat())
        LOG.info("Joined bus %r as %s; members %s", bus, member, member_bus.members)
        return member_bus
    except Exception as e:
        await nc.close()
        if isinstance(e, ConnectionError):
            raise
        raise ConnectionError(f"cannot join bus {bus!r} on {urls}: {e}") from e


def _printable(text: str) -> str:
    """A sender or subject anyone may choose, fit for one log line: printable ASCII, "?" for any other character
    (escape sequences included), at most _PRINTABLE characters and "..." when there were more."""
    clipped = "".join(c if " " <= c <= "~" else "?" for c in text[:_PRINTABLE])
    return clipped + "..." if len(text) > _PRINTABLE else clipped


async def _history(js: Any, stream: str) -> api.ConsumerConfig:
    """Where a member joining a secure bus starts reading: HISTORY_S before the stream's last message (the stream's
    clock, whatever this machine's), or at its first message when it holds none."""
    state = (await js.stream_info(stream)).state
    last = None
    if state.messages > 0:
        try:
            last = (await js.get_msg(stream, seq=state.last_seq)).time
        except NotFoundError:
            pass
    if last is None:
        return api.ConsumerConfig(deliver_policy=api.DeliverPolicy.ALL)
    return api.ConsumerConfig(deliver_policy=api.DeliverPolicy.BY_START_TIME,
                              opt_start_time=last - datetime.timedelta(seconds=HISTORY_S))
