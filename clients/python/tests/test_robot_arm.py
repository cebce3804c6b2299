"""The robot arm plant of the control sample (examples/robot_arm.py) in its own process on a real nats-server, driven
by a controller played by the test with raw NATS messages (test_bus's FakeTester) on this host's clock, so that the
plant's run clock is the test's: its readings come no earlier than its times after the commands, in the model's
order; stop is taken in every state; the stalling arm never arrives."""

from __future__ import annotations

import asyncio
import os
import subprocess
import sys
from pathlib import Path
from typing import Any

import nats

import dtron
from test_bus import FakeTester, run, until

EXAMPLE = Path(__file__).resolve().parent.parent / "examples" / "robot_arm.py"
UNIT_NS = 10_000_000  # 10 ms per model time unit


async def start(nats_url: str, bus: str, home: Path, *flags: str) -> tuple[subprocess.Popen[str], FakeTester, Any]:
    """The arm in its own process, joined and served, and a controller on this host's clock that started a run."""
    arm = subprocess.Popen([sys.executable, str(EXAMPLE), "--bus", nats_url, "--cluster", bus, "--runs", "1", *flags],
                           stdout=subprocess.PIPE, stderr=subprocess.PIPE, text=True, env=dict(os.environ))
    joined = await asyncio.get_running_loop().run_in_executor(None, arm.stdout.readline)  # type: ignore[union-attr]
    assert "joined bus" in joined, joined + arm.stderr.read()  # type: ignore[union-attr]
    nc = await nats.connect(nats_url)
    host = dtron.clock.host_clock_id()
    tester = FakeTester(nc, bus, home, host_clock=host)
    await tester.start()
    await tester.publish("dtron_hello", host_clock=host)
    await until(lambda: any(sorted(s.receives) == ["grip", "move", "release", "stop"]
                            and sorted(s.sends) == ["arrived", "gripped"] for s in tester.on("dtron_serve")))
    await tester.publish("dtron_start", {"timeunit": UNIT_NS // 1000}, run_id="arm-1")
    return arm, tester, nc


def acked(tester: FakeTester, command: Any) -> bool:
    return any(a.acked_sequence == command.sequence for a in tester.on("dtron_ack"))


async def finish(arm: subprocess.Popen[str], tester: FakeTester, nc: Any) -> str:
    await tester.publish("dtron_stop")
    out, err = await asyncio.get_running_loop().run_in_executor(None, arm.communicate, None, 30)
    assert arm.returncode == 0, err
    await nc.close()
    return out


def test_the_arm_answers_its_commands_no_earlier_than_its_times(nats_url: str, dtron_home: Path) -> None:
    async def test() -> None:
        arm, tester, nc = await start(nats_url, "arm", dtron_home, "--travel", "3", "--grip", "1")
        move = await tester.publish("move", run_id="arm-1")
        await until(lambda: len(tester.on("arrived")) == 1)
        assert tester.on("arrived")[0].event_time_ns - move.publish_time_ns >= 3 * UNIT_NS
        grip = await tester.publish("grip", run_id="arm-1")
        await until(lambda: len(tester.on("gripped")) == 1)
        assert tester.on("gripped")[0].event_time_ns - grip.publish_time_ns >= 1 * UNIT_NS
        # a grip while holding is no command of the model: ignored
        again = await tester.publish("grip", run_id="arm-1")
        release = await tester.publish("release", run_id="arm-1")
        await until(lambda: acked(tester, again) and acked(tester, release))
        second = await tester.publish("move", run_id="arm-1")
        await until(lambda: len(tester.on("arrived")) == 2)
        assert tester.on("arrived")[1].event_time_ns - second.publish_time_ns >= 3 * UNIT_NS
        stop = await tester.publish("stop", run_id="arm-1")
        await until(lambda: acked(tester, stop))
        out = await finish(arm, tester, nc)
        assert [name for name, _ in tester.seen if name in ("arrived", "gripped")] == ["arrived", "gripped", "arrived"]
        assert "stopped at t=" in out

    run(test)


def test_the_stalling_arm_never_arrives_and_takes_stop(nats_url: str, dtron_home: Path) -> None:
    async def test() -> None:
        arm, tester, nc = await start(nats_url, "stall", dtron_home, "--stall", "--travel", "3")
        move = await tester.publish("move", run_id="arm-1")
        await until(lambda: acked(tester, move))
        # past the model's bound (5 units): a correct arm would have arrived at 3, before the stop that follows
        await asyncio.sleep(6 * UNIT_NS / 1e9)
        stop = await tester.publish("stop", run_id="arm-1")
        await until(lambda: acked(tester, stop))
        out = await finish(arm, tester, nc)
        assert tester.on("arrived") == []
        assert "stopped at t=" in out

    run(test)
