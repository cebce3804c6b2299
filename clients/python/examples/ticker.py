"""The bundled ticker (models/.../ticker.xml) as a Python bus adapter.

From time 0 of a run it publishes tick(seq) one period after the previous tick (or the start), numbering the ticks
from 1; an input reset restarts the period and the numbering from when it was applied; the run's end stops it. The
ticks are scheduled on the run clock (the tester's time), so a start message that arrives late here, or a host clock
that is off, does not move them. Variant ``correct`` ticks every 10 time units, ``slow`` every 13 (a faulty ticker).

    python ticker.py --bus nats://127.0.0.1:4222 --cluster ticker [--variant slow] [--runs 1] [--key-file PATH]
"""

from __future__ import annotations

import argparse
import asyncio
import logging
import time
from typing import Optional

import dtron

RESET = dtron.Channel("reset")
TICK = dtron.Channel("tick", "seq")
PERIODS = {"correct": 10, "slow": 13}


class Ticker:
    """Ticks on the run clock of a bus member."""

    def __init__(self, bus: dtron.Bus, period: int) -> None:
        self.bus = bus
        self.period = period
        self.seq = 0
        self.last = 0.0
        self.task: Optional[asyncio.Task[None]] = None
        bus.declare_outputs(TICK)
        bus.add_listener(dtron.RUN_START, lambda message: self.restart(0.0))
        bus.add_listener(RESET, self.reset)

    def reset(self, message: dtron.Message) -> None:
        """The tester's reset: acknowledged when this returns, which is when it took effect."""
        if self.bus.run_clock.running:
            self.restart(self.bus.run_clock.now_units())

    def restart(self, from_units: float) -> None:
        """Numbers the ticks from 1 again, the next one due a period after run time ``from_units``."""
        if self.task is not None:
            self.task.cancel()
        self.seq = 0
        self.last = from_units
        self.task = asyncio.get_running_loop().create_task(self.run())

    async def run(self) -> None:
        clock = self.bus.run_clock
        while await clock.sleep_until(self.last + self.period):
            ticked_at = time.time_ns()  # the tick happens now; publishing takes a moment more
            self.seq = (self.seq + 1) % 1000
            sent = await self.bus.send(TICK.value(seq=self.seq), ticked_at)
            self.last = clock.units_of(sent)


async def main() -> None:
    parser = argparse.ArgumentParser(description=__doc__.splitlines()[0])
    parser.add_argument("--bus", default="nats://127.0.0.1:4222", help="NATS server URLs, comma-separated")
    parser.add_argument("--cluster", default="dtron", help="the bus name (dtron run --cluster)")
    parser.add_argument("--variant", default="correct", choices=sorted(PERIODS))
    parser.add_argument("--runs", type=int, default=0, help="exit after this many runs (0: never)")
    parser.add_argument("--key-file", help="the bus's secret (default ~/.dtron/bus.key, made if there is none)")
    args = parser.parse_args()
    logging.basicConfig(level=logging.INFO, format="%(asctime)s %(levelname)s %(message)s")
    async with await dtron.connect(args.bus, bus=args.cluster, key_file=args.key_file) as bus:
        Ticker(bus, PERIODS[args.variant])
        runs_over = asyncio.Event()
        stops = 0

        def stopped(message: dtron.Message) -> None:
            nonlocal stops
            stops += 1
            if args.runs and stops >= args.runs:
                runs_over.set()

        bus.add_listener(dtron.RUN_STOP, stopped)
        print(f"ticker {args.variant} joined bus {args.cluster!r} as {bus.member}", flush=True)
        await runs_over.wait()


if __name__ == "__main__":
    try:
        asyncio.run(main())
    except (ValueError, ConnectionError) as e:  # a key file, bus or server that cannot be used: one line
        raise SystemExit(f"ticker: {e}")
