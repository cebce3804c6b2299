"""Python members on a real nats-server: order, membership, the handshake, clock offsets, acknowledgements and
rejected input, against a tester played by the test with raw NATS messages, signed with the bus's secret."""

from __future__ import annotations

import asyncio
import time
from pathlib import Path
from typing import Any, Callable, Coroutine

import nats
import pytest

import dtron
from conftest import Signer, bus_secret
from dtron._proto import Sync_pb2

ORDER = dtron.Channel("order", "n")
RESET = dtron.Channel("reset")
TICK = dtron.Channel("tick", "seq")


def run(test: Callable[[], Coroutine[Any, Any, None]]) -> None:
    asyncio.run(asyncio.wait_for(test(), timeout=60))


async def until(condition: Callable[[], bool], seconds: float = 10) -> None:
    deadline = time.monotonic() + seconds
    while not condition():
        assert time.monotonic() < deadline, "condition not met in time"
        await asyncio.sleep(0.01)


class FakeTester:
    """A tester played with raw NATS: publishes Sync messages and records what the others publish. As another
    ``member`` (``tester`` False), a member that is not the tester, which answers no ping: a live monitor."""

    def __init__(self, nc: Any, bus: str, home: Path, clock_shift_ns: int = 0, host_clock: str = "",
                 member: str = "tester", tester: bool = True) -> None:
        self.nc = nc
        self.host_clock = host_clock
        self.member = member
        self.tester = tester
        self.signer = Signer(bus_secret(home), member)
        self.js = nc.jetstream()
        self.bus = bus
        self.shift = clock_shift_ns
        self.sequence = 0
        self.seen: list[tuple[str, Any]] = []

    async def start(self) -> None:
        await self.js.subscribe(f"dtron.{self.bus}.c.>", cb=self.received, ordered_consumer=True,
                                deliver_policy=nats.js.api.DeliverPolicy.NEW)

    async def received(self, msg: Any) -> None:
        channel = msg.subject.rsplit(".", 1)[1]
        sync = Sync_pb2.Sync.FromString(msg.data)
        self.seen.append((channel, sync))
        if channel == "dtron_ping" and self.tester and sync.sender != self.member:
            await self.publish("dtron_pong", event_time_ns=time.time_ns() + self.shift, acked_sender=sync.sender,
                               acked_sequence=sync.sequence, host_clock=self.host_clock)

    async def publish(self, channel: str, variables: dict[str, int] | None = None, **fields: Any) -> Sync_pb2.Sync:
        self.sequence += 1
        sync = Sync_pb2.Sync(name=channel, sender=self.member, sequence=self.sequence,
                             publish_time_ns=time.time_ns() + self.shift, **fields)
        for name, value in (variables or {}).items():
            sync.variables.add(name=name, value=value)
        await self.publish_raw(f"dtron.{self.bus}.c.{channel}", sync.SerializeToString())
        return sync

    async def publish_raw(self, subject: str, data: bytes) -> None:
        await self.js.publish(subject, data, headers=self.signer.headers(subject, data))

    def on(self, channel: str) -> list[Any]:
        return [sync for name, sync in self.seen if name == channel]


def test_members_see_one_order_and_each_other_join_and_leave(nats_url: str) -> None:
    async def test() -> None:
        a = await dtron.connect(nats_url, bus="order", member="a")
        b = await dtron.connect(nats_url, bus="order", member="b")
        seen: dict[str, list[str]] = {"a": [], "b": []}
        a.add_listener(ORDER, lambda m: seen["a"].append(f"{m.sender}:{m.variables['n']}"))

        @b.listener(ORDER)
        async def record(m: dtron.Message) -> None:
            seen["b"].append(f"{m.sender}:{m.variables['n']}")

        await until(lambda: a.members == ["a", "b"] and b.members == ["a", "b"])

        async def burst(bus: dtron.Bus) -> None:
            for n in range(1, 101):
                await bus.send(ORDER.value(n=n))

        await asyncio.gather(burst(a), burst(b))
        await until(lambda: len(seen["a"]) == 200 and len(seen["b"]) == 200)
        assert seen["a"] == seen["b"]
        assert len(set(seen["a"])) == 200
        await b.close()
        await until(lambda: a.members == ["a"])
        assert a.stats.published == 100 and a.stats.accepted == 200
        await a.close()

    run(test)


def test_the_handshake_the_clock_offset_and_acknowledgements(nats_url: str, dtron_home: Path) -> None:
    async def test() -> None:
        nc = await nats.connect(nats_url)
        adapter = await dtron.connect(nats_url, bus="hand", member="adapter")
        tester = FakeTester(nc, "hand", dtron_home, clock_shift_ns=50_000_000)
        await tester.start()
        adapter.declare_outputs(TICK)
        resets: list[dtron.Message] = []
        adapter.add_listener(RESET, resets.append)
        await tester.publish("dtron_hello")
        await until(lambda: any(list(s.receives) == ["reset"] and list(s.sends) == ["tick"]
                                for s in tester.on("dtron_serve")))
        # the adapter pings the tester it learned from the hello; the tester's clock is 50 ms ahead
        await until(lambda: adapter.clock_offset is not None and len(tester.on("dtron_ping")) >= 8)
        offset = adapter.clock_offset
        assert offset is not None and offset.tester == "tester"
        assert abs(offset.offset_ns - 50_000_000) <= offset.error_ns, offset
        start = await tester.publish("dtron_start", {"timeunit": 1000}, run_id="run-1")
        await until(lambda: adapter.run_clock.running)
        assert abs(adapter.run_clock.now_ns() - (time.time_ns() + 50_000_000 - start.publish_time_ns)) < 20_000_000
        reset = await tester.publish("reset", run_id="run-1")
        await until(lambda: len(tester.on("dtron_ack")) == 1)
        ack = tester.on("dtron_ack")[0]
        assert (ack.acked_sender, ack.acked_sequence, ack.run_id) == ("tester", reset.sequence, "run-1")
        assert ack.clock_error_ns > 0 and abs(ack.clock_offset_ns - 50_000_000) <= ack.clock_error_ns
        assert len(resets) == 1 and resets[0].sender == "tester"
        # messages of another run (as replayed from an earlier one) neither reach the listener nor end this run
        await tester.publish("reset", run_id="run-0")
        await tester.publish("dtron_stop", run_id="run-0")
        await tester.publish("reset", run_id="run-1")
        await until(lambda: len(resets) == 2)
        assert adapter.run_clock.running and [r.run_id for r in resets] == ["run-1", "run-1"]
        await tester.publish("dtron_stop", run_id="run-1")
        await until(lambda: not adapter.run_clock.running)
        await adapter.close()
        await nc.close()

    run(test)


def test_a_member_answers_its_testers_pings_and_a_monitors_probe_but_not_its_other_pings(nats_url: str,
                                                                                          dtron_home: Path) -> None:
    async def test() -> None:
        nc = await nats.connect(nats_url)
        adapter = await dtron.connect(nats_url, bus="probe", member="adapter")
        tester = FakeTester(nc, "probe", dtron_home)
        monitor = FakeTester(nc, "probe", dtron_home, member="monitor", tester=False)
        await tester.start()
        await monitor.start()
        await tester.publish("dtron_hello")
        await until(lambda: adapter.clock_offset is not None)
        # a monitor's ping of its own, its probe (a live monitor's before a deadline), then the tester's ping
        await monitor.publish("dtron_ping")
        probe = await monitor.publish("dtron_ping", probe=True)
        asked = await tester.publish("dtron_ping")

        def answers() -> list[tuple[str, int]]:
            return [(p.acked_sender, p.acked_sequence) for p in tester.on("dtron_pong") if p.sender == "adapter"]

        await until(lambda: ("tester", asked.sequence) in answers())
        # the answers come in the pings' order: the probe's and the tester's; the monitor's other ping has none
        assert answers() == [("monitor", probe.sequence), ("tester", asked.sequence)]
        await adapter.close()
        await nc.close()

    run(test)


def test_a_tester_reading_this_hosts_clock_gives_an_exact_offset_while_round_trips_agree(nats_url: str,
                                                                                         dtron_home: Path) -> None:
    async def test() -> None:
        nc = await nats.connect(nats_url)
        host = dtron.clock.host_clock_id()
        assert host.startswith("linux-boot:")
        # a tester on this host says so on its pongs: offset 0, give or take the clock's microsecond
        same = await dtron.connect(nats_url, bus="same", member="adapter")
        tester = FakeTester(nc, "same", dtron_home, host_clock=host)
        await tester.start()
        await tester.publish("dtron_hello", host_clock=host)
        await until(lambda: same.clock_offset is not None)
        assert same.clock_offset == dtron.ClockOffset("tester", 0, 1_000)
        # one that says so but whose readings lie 50 ms outside the round trips is estimated from them
        liar = await dtron.connect(nats_url, bus="liar", member="adapter")
        shifted = FakeTester(nc, "liar", dtron_home, clock_shift_ns=50_000_000, host_clock=host)
        await shifted.start()
        await shifted.publish("dtron_hello", host_clock=host)
        await until(lambda: liar.clock_offset is not None)
        offset = liar.clock_offset
        assert offset.error_ns > 1_000 and abs(offset.offset_ns - 50_000_000) <= offset.error_ns, offset
        await same.close()
        await liar.close()
        await nc.close()

    run(test)


def test_bad_input_is_rejected_and_counted_and_the_rest_delivered(nats_url: str, dtron_home: Path) -> None:
    async def test() -> None:
        nc = await nats.connect(nats_url)
        adapter = await dtron.connect(nats_url, bus="bad", member="adapter")
        got: list[dtron.Message] = []
        adapter.add_listener(ORDER, got.append)
        tester = FakeTester(nc, "bad", dtron_home)
        await tester.publish_raw("dtron.bad.c.order", b"\xff\x01\x02")
        await tester.publish("order", {"n": 1, "m": 2})
        await tester.publish("order", {})
        await tester.publish("order", {"n": 7})
        await until(lambda: len(got) == 1)
        assert got[0].variables == {"n": 7}
        assert adapter.stats.rejected == {"MALFORMED": 1, "UNKNOWN_VARIABLES": 1, "MISSING_VARIABLES": 1}
        assert adapter.stats.accepted == 1
        await adapter.close()
        await nc.close()

    run(test)


def test_unreachable_servers_and_bad_names_are_refused() -> None:
    async def test() -> None:
        with pytest.raises(ValueError):
            await dtron.connect("nats://127.0.0.1:1", bus="no.dots")
        with pytest.raises(ConnectionError):
            await dtron.connect("nats://127.0.0.1:1", bus="none")

    run(test)


def test_a_server_with_a_user_takes_only_members_with_its_password(nats_url_with_user: str) -> None:
    async def test() -> None:
        with pytest.raises(ConnectionError):
            await dtron.connect(nats_url_with_user, bus="auth")
        with pytest.raises(ConnectionError):
            await dtron.connect(nats_url_with_user, bus="auth", user="lab", password="guess")
        async with await dtron.connect(nats_url_with_user, bus="auth", member="m", user="lab",
                                       password="s3cret") as bus:
            assert bus.members == ["m"]

    run(test)


def test_a_server_with_a_token_takes_only_members_with_it(nats_url_with_token: str) -> None:
    async def test() -> None:
        with pytest.raises(ConnectionError):
            await dtron.connect(nats_url_with_token, bus="auth")
        with pytest.raises(ConnectionError):
            await dtron.connect(nats_url_with_token, bus="auth", token="guess")
        async with await dtron.connect(nats_url_with_token, bus="auth", member="m", token="t0ken-s3cret") as bus:
            assert bus.members == ["m"]

    run(test)


def test_tls_to_the_servers_trusts_the_given_authority_only(nats_tls: tuple[str, Any, Any]) -> None:
    url, ca, other_ca = nats_tls

    async def test() -> None:
        with pytest.raises(ConnectionError):
            await dtron.connect(url, bus="tls", tls_ca=str(other_ca))
        async with await dtron.connect(url, bus="tls", member="a", tls_ca=str(ca)) as a, \
                await dtron.connect(url, bus="tls", member="b", tls_ca=str(ca)) as b:
            got: list[int] = []
            b.add_listener(ORDER, lambda m: got.append(m.variables["n"]))
            await until(lambda: a.members == ["a", "b"])
            await a.send(ORDER.value(n=7))
            await until(lambda: got == [7])

    run(test)
