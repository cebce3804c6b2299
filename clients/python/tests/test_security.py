"""The bus's secret (page "Security: the bus's secret"): the key file, the message codes against known answers
computed apart from the client (with openssl), and on a real nats-server: a stranger, a replayed message, a stale
one and an insecure member are dropped, counted, named once in the log, and change neither the members nor what
a listener gets."""

from __future__ import annotations

import logging
import os
import stat
import time
from concurrent.futures import ThreadPoolExecutor
from pathlib import Path
from typing import Any

import nats
import pytest

import dtron
from conftest import Signer, bus_secret
from dtron import secret
from dtron._proto import Sync_pb2
from test_bus import ORDER, run, until

# Known answers, computed with openssl (dgst -sha256 -mac HMAC): the secret is the key file's text as UTF-8 bytes.
SECRET = b"00112233445566778899aabbccddeeff00112233445566778899aabbccddeeff"
K = "0a1c59bef3f2d1c4598317cdffe91c2dc82e4c94b329ab6d90ba518a82de1246"
TICK_SYNC = bytes.fromhex("0a047469636b")  # Sync{name: "tick"}
VECTORS = [
    ("dtron.ticker.c.tick", {"Dtron-Sender": "dtron-py-4711-9f1c2a3b", "Dtron-Seq": "7",
                             "Dtron-Time": "1700000000123456789"}, TICK_SYNC,
     "7e1dec17aae65de5c2f22c1d7fe50605b20d698688765899136e543360a390aa"),
    ("dtron.ticker.p", {"Dtron-Sender": "tester-1", "Dtron-Seq": "12", "Dtron-Time": "1700000000000000000",
                        "Dtron-Presence": "alive", "Dtron-Joined": "3"}, b"",
     "130f94379dba282fe38e8079a4d174e0ade245256240904109825ef1a53dabc5"),
]


def test_the_codes_are_the_known_answers(tmp_path: Path) -> None:
    assert secret.mac_key(SECRET).hex() == K
    for subject, headers, data, code in VECTORS:
        assert secret.message_code(secret.mac_key(SECRET), subject, headers, data) == code
        assert Signer(SECRET, headers["Dtron-Sender"]).headers(
            subject, data, headers.get("Dtron-Presence"), headers.get("Dtron-Joined"),
            int(headers["Dtron-Time"]), int(headers["Dtron-Seq"]))["Dtron-Mac"] == code
    # the key file's content without the white space around it
    key_file = tmp_path / "given.key"
    key_file.write_bytes(b"  " + SECRET + b"\n\n")
    key_file.chmod(0o600)
    assert secret.load_secret(key_file) == SECRET


def test_the_default_key_file_is_made_on_first_use(dtron_home: Path) -> None:
    assert dtron.default_key_file() == dtron_home / "bus.key"
    assert not dtron_home.exists()
    made = secret.load_secret()
    assert stat.S_IMODE(dtron_home.stat().st_mode) == 0o700
    assert stat.S_IMODE((dtron_home / "bus.key").stat().st_mode) == 0o600
    text = (dtron_home / "bus.key").read_text()
    assert len(text) == 65 and text.endswith("\n") and all(c in "0123456789abcdef" for c in text[:64])
    assert made == text[:64].encode()
    assert secret.load_secret() == made
    assert os.listdir(dtron_home) == ["bus.key"]


def test_racing_members_all_use_the_one_key_file(dtron_home: Path) -> None:
    with ThreadPoolExecutor(8) as pool:
        secrets = list(pool.map(lambda _: secret.load_secret(), range(16)))
    assert set(secrets) == {bus_secret(dtron_home)}
    assert os.listdir(dtron_home) == ["bus.key"]


def test_a_key_file_others_may_read_or_write_an_empty_or_a_missing_one_is_refused(tmp_path: Path) -> None:
    key_file = tmp_path / "bus.key"
    key_file.write_bytes(SECRET)
    for mode in (0o640, 0o604, 0o620, 0o602):
        key_file.chmod(mode)
        with pytest.raises(dtron.KeyFileError) as refused:
            secret.load_secret(key_file)
        assert str(key_file) in str(refused.value) and f"chmod 600 {key_file}" in str(refused.value)
        assert "\n" not in str(refused.value)
    key_file.chmod(0o600)
    assert secret.load_secret(key_file) == SECRET
    key_file.write_bytes(b" \n")
    with pytest.raises(dtron.KeyFileError, match=f"key file {key_file} is empty"):
        secret.load_secret(key_file)
    missing = tmp_path / "none" / "bus.key"
    with pytest.raises(dtron.KeyFileError, match=f"key file {missing} does not exist"):
        secret.load_secret(missing)
    assert not missing.parent.exists()  # a named file is never made


def test_connect_refuses_a_bad_key_file_before_it_connects(tmp_path: Path, dtron_home: Path) -> None:
    key_file = tmp_path / "open.key"
    key_file.write_bytes(SECRET)
    key_file.chmod(0o644)

    async def test() -> None:
        with pytest.raises(dtron.KeyFileError, match=f"chmod 600 {key_file}"):
            await dtron.connect("nats://127.0.0.1:1", bus="any", key_file=key_file)
        with pytest.raises(ValueError):
            await dtron.connect("nats://127.0.0.1:1", bus="any", key_file=key_file, insecure=True)

    run(test)
    assert not dtron_home.exists()  # a member given a key file makes none


def test_a_member_numbers_its_messages_from_its_clock_at_start() -> None:
    before = time.time_ns()
    guard = secret.Guard(SECRET)
    after = time.time_ns()
    first = guard.sign("s", {"Dtron-Sender": "m"}, b"x", 5)
    second = guard.sign("s", {"Dtron-Sender": "m"}, b"x", 6)
    assert before <= int(first["Dtron-Seq"]) <= after and int(second["Dtron-Seq"]) == int(first["Dtron-Seq"]) + 1
    assert first["Dtron-Time"] == "5" and first["Dtron-Sender"] == "m"
    expected = Signer(SECRET, "m").headers("s", b"x", time_ns=5, seq=int(first["Dtron-Seq"]))
    assert first == expected


def test_the_window_of_numbers_takes_each_number_once() -> None:
    guard = secret.Guard(SECRET)
    signer = Signer(SECRET, "m")
    now = time.time_ns()

    def check(seq: int) -> Any:
        headers = signer.headers("s", b"", time_ns=now, seq=seq)
        return guard.check("s", headers, b"", now)

    assert [check(n) for n in (1, 3, 2, 3, 1)] == [None, None, None, "REPLAYED", "REPLAYED"]
    assert check(5000) is None
    assert [check(5000 - 4095), check(5000 - 4096), check(4)] == [None, "REPLAYED", "REPLAYED"]
    assert check(0) == "REPLAYED"
    assert guard.check("s", {"Dtron-Sender": "m", "Dtron-Seq": "9", "Dtron-Time": str(now)}, b"", now) \
        == "UNAUTHENTICATED"


def dropped_lines(caplog: pytest.LogCaptureFixture, sender: str, reason: str) -> list[str]:
    return [r.getMessage() for r in caplog.records
            if r.name == "dtron" and f"from {sender!r}, {reason}" in r.getMessage()]


def test_a_stranger_is_refused_and_changes_neither_members_nor_listeners(
        nats_url: str, tmp_path: Path, caplog: pytest.LogCaptureFixture) -> None:
    caplog.set_level(logging.WARNING, logger="dtron")
    stranger_key = tmp_path / "stranger.key"
    stranger_key.write_text("not the bus's secret\n")
    stranger_key.chmod(0o600)

    async def test() -> None:
        a = await dtron.connect(nats_url, bus="sec", member="a")
        b = await dtron.connect(nats_url, bus="sec", member="b")
        got: list[str] = []
        a.add_listener(ORDER, lambda m: got.append(f"{m.sender}:{m.variables['n']}"))
        await until(lambda: a.members == ["a", "b"] and b.members == ["a", "b"])
        # a whole member with another key file: its join, announcement and message are forgeries
        stranger = await dtron.connect(nats_url, bus="sec", member="stranger", key_file=stranger_key)
        stranger_got: list[str] = []
        stranger.add_listener(ORDER, lambda m: stranger_got.append(f"{m.sender}:{m.variables['n']}"))
        await stranger.send(ORDER.value(n=666))
        # and forgeries made by hand: a presence and a channel message with the stranger's codes, one without any
        nc = await nats.connect(nats_url)
        js = nc.jetstream()
        forger = Signer(b"a third secret", "tester")
        data = Sync_pb2.Sync(name="order", sender="tester", sequence=1, publish_time_ns=time.time_ns(),
                             variables=[Sync_pb2.Variable(name="n", value=13)]).SerializeToString()
        await js.publish("dtron.sec.p", b"", headers=forger.headers("dtron.sec.p", b"", presence="join"))
        await js.publish("dtron.sec.c.order", data, headers=forger.headers("dtron.sec.c.order", data))
        await js.publish("dtron.sec.c.order", data, headers={"Dtron-Sender": "tester", "Dtron-Seq": "2",
                                                               "Dtron-Time": str(time.time_ns())})
        await b.send(ORDER.value(n=1))  # after every forgery in the stream's order
        await until(lambda: got == ["b:1"] and b.stats.rejected.get("UNAUTHENTICATED", 0) >= 5)
        await stranger.send(ORDER.value(n=667))
        await b.send(ORDER.value(n=2))
        await until(lambda: got == ["b:1", "b:2"])
        for member in (a, b):
            assert member.members == ["a", "b"]
            assert set(member.stats.rejected) == {"UNAUTHENTICATED"}
            assert member.stats.rejected["UNAUTHENTICATED"] >= 6
        # the stranger hears no one either, nor the forger
        assert stranger.members == ["stranger"] and stranger_got == ["stranger:666", "stranger:667"]
        assert stranger.stats.rejected.get("UNAUTHENTICATED", 0) >= 2
        await nc.close()
        await stranger.close()
        await b.close()
        await until(lambda: a.members == ["a"])
        await a.close()

    run(test)
    assert len(dropped_lines(caplog, "stranger", "UNAUTHENTICATED")) == 2  # once by a, once by b
    assert len(dropped_lines(caplog, "tester", "UNAUTHENTICATED")) == 3  # by a, b and the stranger


async def capturing(nats_url: str, subject: str) -> tuple[Any, list[Any]]:
    """A client without the secret, and the list into which it captures the messages on ``subject`` from now on."""
    nc = await nats.connect(nats_url)
    captured: list[Any] = []

    async def capture(msg: Any) -> None:
        captured.append(msg)

    await nc.subscribe(subject, cb=capture)
    await nc.flush()
    return nc, captured


def test_a_replayed_message_is_dropped_as_replayed(nats_url: str, caplog: pytest.LogCaptureFixture) -> None:
    caplog.set_level(logging.WARNING, logger="dtron")

    async def test() -> None:
        a = await dtron.connect(nats_url, bus="replay", member="a")
        b = await dtron.connect(nats_url, bus="replay", member="b")
        got: list[int] = []
        b.add_listener(ORDER, lambda m: got.append(m.variables["n"]))
        await until(lambda: b.members == ["a", "b"])
        nc, captured = await capturing(nats_url, "dtron.replay.c.order")
        await a.send(ORDER.value(n=1))
        await until(lambda: got == [1] and len(captured) == 1)
        # published again as captured, under a new Nats-Msg-Id (which the code does not cover), twice
        headers = {k: v for k, v in captured[0].headers.items() if k != "Nats-Msg-Id"}
        for _ in range(2):
            await nc.jetstream().publish("dtron.replay.c.order", captured[0].data, headers=headers)
        await a.send(ORDER.value(n=2))
        await until(lambda: got == [1, 2])
        assert b.stats.rejected == {"REPLAYED": 2} and b.stats.accepted == 2
        assert b.members == ["a", "b"]
        await nc.close()
        await b.close()
        await a.close()

    run(test)
    assert len(dropped_lines(caplog, "a", "REPLAYED")) == 2  # once by a (its own message), once by b


def test_a_message_from_before_a_member_joined_published_again_is_replayed_for_it(nats_url: str) -> None:
    """A member that joins later learns the numbers of the stream's messages before its join (without delivering
    them): a finished run's start, published again after it joined, is replayed for it, as the order before it."""
    async def test() -> None:
        a = await dtron.connect(nats_url, bus="late", member="a")
        nc, captured = await capturing(nats_url, "dtron.late.c.>")
        await a.send(ORDER.value(n=1))
        await a.send(dtron.RUN_START.value(timeunit=1000))
        await until(lambda: any(msg.subject == "dtron.late.c.dtron_start" for msg in captured))
        before = list(captured)  # the order, the start and what else a published (the channels it sends)
        late = await dtron.connect(nats_url, bus="late", member="late")
        got: list[str] = []
        late.add_listener(ORDER, lambda m: got.append(f"order {m.variables['n']}"))
        late.add_listener(dtron.RUN_START, lambda m: got.append("start"))
        for msg in before:  # as captured, under a new Nats-Msg-Id (which the code does not cover)
            headers = {k: v for k, v in msg.headers.items() if k != "Nats-Msg-Id"}
            await nc.jetstream().publish(msg.subject, msg.data, headers=headers)
        await a.send(ORDER.value(n=2))
        await until(lambda: got == ["order 2"])
        assert late.stats.rejected == {"REPLAYED": len(before)}
        await nc.close()
        await late.close()
        await a.close()

    run(test)


def test_a_member_that_joined_later_hears_the_bus_after_its_consumer_was_made_anew(nats_url: str) -> None:
    """A member that joins a bus whose stream holds messages reads it from a start time; when the server loses its
    consumer, the client makes it anew from a sequence, which the server takes only without that start time."""
    async def test() -> None:
        a = await dtron.connect(nats_url, bus="anew", member="a")
        b = await dtron.connect(nats_url, bus="anew", member="b")  # the stream holds a's messages
        got: list[int] = []
        b.add_listener(ORDER, lambda m: got.append(m.variables["n"]))
        await until(lambda: b.members == ["a", "b"])
        nc = await nats.connect(nats_url)
        js = nc.jetstream()
        for consumer in await js.consumers_info("DTRON_anew"):
            await js.delete_consumer("DTRON_anew", consumer.name)
        await a.send(ORDER.value(n=1))
        await until(lambda: got == [1], 60)
        assert got == [1] and b.stats.rejected == {}
        await nc.close()
        await b.close()
        await a.close()

    run(test)


def test_a_member_started_again_under_its_id_is_heard(nats_url: str) -> None:
    async def test() -> None:
        b = await dtron.connect(nats_url, bus="again", member="b")
        got: list[str] = []
        b.add_listener(ORDER, lambda m: got.append(f"{m.sender}:{m.variables['n']}"))
        for n in (1, 2):
            a = await dtron.connect(nats_url, bus="again", member="a")
            await until(lambda: b.members == ["b", "a"])
            await a.send(ORDER.value(n=n))
            await until(lambda: len(got) == n)
            await a.close()
            await until(lambda: b.members == ["b"])
        assert got == ["a:1", "a:2"] and b.stats.rejected == {}
        await b.close()

    run(test)


def test_a_stale_message_is_dropped_as_stale(nats_url: str, dtron_home: Path) -> None:
    async def test() -> None:
        b = await dtron.connect(nats_url, bus="stale", member="b")
        got: list[int] = []
        b.add_listener(ORDER, lambda m: got.append(m.variables["n"]))
        nc = await nats.connect(nats_url)
        signer = Signer(bus_secret(dtron_home), "old")
        for n, shift_s in ((1, -200), (2, 200), (3, -121), (4, 0)):
            data = Sync_pb2.Sync(name="order", sender="old", sequence=n, publish_time_ns=time.time_ns(),
                                 variables=[Sync_pb2.Variable(name="n", value=n)]).SerializeToString()
            headers = signer.headers("dtron.stale.c.order", data, time_ns=time.time_ns() + shift_s * 1_000_000_000)
            await nc.jetstream().publish("dtron.stale.c.order", data, headers=headers)
        await until(lambda: got == [4])
        assert b.stats.rejected == {"STALE": 3}
        await nc.close()
        await b.close()

    run(test)


def test_an_insecure_member_and_a_secure_one_do_not_hear_each_other(
        nats_url: str, caplog: pytest.LogCaptureFixture) -> None:
    caplog.set_level(logging.WARNING, logger="dtron")

    async def test() -> None:
        secure = await dtron.connect(nats_url, bus="mixed", member="secure")
        insecure = await dtron.connect(nats_url, bus="mixed", member="insecure", insecure=True)
        heard: dict[str, list[str]] = {"secure": [], "insecure": []}
        for member in (secure, insecure):
            member.add_listener(ORDER, lambda m, me=member.member: heard[me].append(m.sender))
        await secure.send(ORDER.value(n=1))
        await insecure.send(ORDER.value(n=1))
        await until(lambda: heard == {"secure": ["secure"], "insecure": ["insecure"]}
                    and secure.stats.rejected.get("UNAUTHENTICATED", 0) >= 3
                    and insecure.stats.rejected.get("UNAUTHENTICATED", 0) >= 3)
        assert secure.members == ["secure"] and insecure.members == ["insecure"]
        await insecure.close()
        await secure.close()

    run(test)
    assert any("INSECURE: member insecure on bus 'mixed'" in r.getMessage() for r in caplog.records)


def test_a_senders_name_anyone_may_choose_is_logged_printable_and_clipped(
        nats_url: str, caplog: pytest.LogCaptureFixture) -> None:
    caplog.set_level(logging.WARNING, logger="dtron")
    name = "\x1b[31mred" + "x" * 1000  # an escape sequence of the terminal, and far too long for a line

    async def test() -> None:
        b = await dtron.connect(nats_url, bus="names", member="b")
        nc = await nats.connect(nats_url)
        await nc.jetstream().publish("dtron.names.c.order", b"", headers={"Dtron-Sender": name})
        await until(lambda: b.stats.rejected.get("UNAUTHENTICATED", 0) == 1)
        await nc.close()
        await b.close()

    run(test)
    lines = [r.getMessage() for r in caplog.records if r.name == "dtron" and "dropped a message" in r.getMessage()]
    assert len(lines) == 1 and "\x1b" not in lines[0]
    assert "from '?[31mred" + "x" * 120 + "...', UNAUTHENTICATED" in lines[0]
