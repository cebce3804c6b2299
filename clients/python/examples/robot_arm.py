"""The robot arm of DTRON's control sample (models/.../robotarm/robot-arm.xta) as a plant on the bus.

It takes the controller's commands move, grip, release and stop, and its sensors answer: arrived ``--travel`` time
units after a move (the model allows 2 to 5; default 3), gripped ``--grip`` units after a grip (1 to 2; default 1).
The times are on the run clock (the controller's time), counted from when the command was applied. A command the arm
cannot take in its state is logged and ignored; stop stops the arm for the rest of the run. ``--stall`` makes an arm
that never arrives: the controller raises the alarm 5 units after its move and sends its safe action, stop.

    python robot_arm.py --bus nats://127.0.0.1:4222 --cluster arm [--stall] [--travel 3] [--grip 1] [--runs 1]
"""

from __future__ import annotations

import argparse
import asyncio
import logging
import time
from typing import Optional

import dtron

MOVE = dtron.Channel("move")
GRIP = dtron.Channel("grip")
RELEASE = dtron.Channel("release")
STOP = dtron.Channel("stop")
ARRIVED = dtron.Channel("arrived")
GRIPPED = dtron.Channel("gripped")

log = logging.getLogger("robot_arm")


class RobotArm:
    """The arm's states (ready, moving, arrived, gripping, holding, stopped) and its sensors, on a bus member."""

    def __init__(self, bus: dtron.Bus, travel: float, grip: float, stall: bool) -> None:
        self.bus = bus
        self.travel = travel
        self.grip_time = grip
        self.stall = stall
        self.state = "ready"
        self.task: Optional[asyncio.Task[None]] = None
        bus.declare_outputs(ARRIVED, GRIPPED)
        bus.add_listener(dtron.RUN_START, lambda message: self.begin())
        bus.add_listener(MOVE, self.move)
        bus.add_listener(GRIP, self.grip)
        bus.add_listener(RELEASE, self.release)
        bus.add_listener(STOP, self.stop)

    def begin(self) -> None:
        """A run starts: the arm is ready, nothing in its hand."""
        self.cancel()
        self.state = "ready"

    def move(self, message: dtron.Message) -> None:
        if self.expect("ready", message):
            self.state = "moving"
            if not self.stall:
                self.after(self.travel, ARRIVED, "arrived")

    def grip(self, message: dtron.Message) -> None:
        if self.expect("arrived", message):
            self.state = "gripping"
            self.after(self.grip_time, GRIPPED, "holding")

    def release(self, message: dtron.Message) -> None:
        if self.expect("holding", message):
            self.state = "ready"

    def stop(self, message: dtron.Message) -> None:
        """The safe action: taken in every state; the arm stays stopped until the next run."""
        self.cancel()
        self.state = "stopped"
        print(f"stopped at t={self.bus.run_clock.now_units():.3f}", flush=True)

    def expect(self, state: str, message: dtron.Message) -> bool:
        if self.state != state:
            log.warning("%s in state %s: ignored", message.name, self.state)
            return False
        return True

    def after(self, units: float, reading: dtron.Channel, state: str) -> None:
        """Sends ``reading`` ``units`` from now on the run clock, then is in ``state``."""
        due = self.bus.run_clock.now_units() + units
        self.cancel()
        self.task = asyncio.get_running_loop().create_task(self.sense(due, reading, state))

    async def sense(self, due: float, reading: dtron.Channel, state: str) -> None:
        if await self.bus.run_clock.sleep_until(due):
            happened = time.time_ns()  # the sensor fires now; publishing takes a moment more
            self.state = state
            await self.bus.send(reading.value(), happened)

    def cancel(self) -> None:
        if self.task is not None:
            self.task.cancel()
            self.task = None


async def main() -> None:
    parser = argparse.ArgumentParser(description=__doc__.splitlines()[0])
    parser.add_argument("--bus", default="nats://127.0.0.1:4222", help="NATS server URLs, comma-separated")
    parser.add_argument("--cluster", default="dtron", help="the bus name")
    parser.add_argument("--travel", type=float, default=3.0, help="time units from move to arrived")
    parser.add_argument("--grip", type=float, default=1.0, help="time units from grip to gripped")
    parser.add_argument("--stall", action="store_true", help="never arrive: a stalling arm")
    parser.add_argument("--runs", type=int, default=0, help="exit after this many runs (0: never)")
    parser.add_argument("--key-file", help="the bus's secret (default ~/.dtron/bus.key, made if there is none)")
    args = parser.parse_args()
    if args.travel < 0 or args.grip < 0:
        raise ValueError("--travel and --grip must not be negative")
    logging.basicConfig(level=logging.INFO, format="%(asctime)s %(levelname)s %(message)s")
    async with await dtron.connect(args.bus, bus=args.cluster, key_file=args.key_file) as bus:
        RobotArm(bus, args.travel, args.grip, args.stall)
        runs_over = asyncio.Event()
        stops = 0

        def stopped(message: dtron.Message) -> None:
            nonlocal stops
            stops += 1
            if args.runs and stops >= args.runs:
                runs_over.set()

        bus.add_listener(dtron.RUN_STOP, stopped)
        print(f"robot arm{' (stalling)' if args.stall else ''} joined bus {args.cluster!r} as {bus.member}",
              flush=True)
        await runs_over.wait()


if __name__ == "__main__":
    try:
        asyncio.run(main())
    except (ValueError, ConnectionError) as e:  # a key file, bus or server that cannot be used: one line
        raise SystemExit(f"robot_arm: {e}")
