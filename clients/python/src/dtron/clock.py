"""The clock-offset estimate and the run clock: the tester's time of a test run, as DTRON's Java API keeps it."""

from __future__ import annotations

import asyncio
import time
from collections import deque
from dataclasses import dataclass
from typing import Callable, Optional

#: How many of the latest samples the estimate is chosen from.
WINDOW = 8


@dataclass(frozen=True)
class ClockOffset:
    """An estimate of (tester's wall clock - this member's), and its error bound, in nanoseconds."""

    tester: str
    offset_ns: int
    error_ns: int


class OffsetEstimator:
    """Estimates the offset from ping round trips: the sample with the shortest round trip among the last few.

    A sample is ``offset = ((t_tester - t0) + (t_tester - t3)) / 2`` with ``t0`` the ping's send time and ``t3`` the
    pong's receive time on the own clock, ``t_tester`` the tester's clock when the ping arrived; the true offset lies
    within half the round trip of it.
    """

    def __init__(self) -> None:
        self._samples: deque[tuple[int, int]] = deque(maxlen=WINDOW)

    def add(self, t0: int, tester_time: int, t3: int) -> Optional[tuple[int, int]]:
        """Adds a sample (a negative round trip is ignored) and returns the estimate (offset, error) now."""
        round_trip = t3 - t0
        if round_trip >= 0:
            self._samples.append(((tester_time - t0 + tester_time - t3) // 2, round_trip))
        return self.estimate()

    def estimate(self) -> Optional[tuple[int, int]]:
        """The estimate (offset, error bound >= 1) of the samples in the window, or None."""
        if not self._samples:
            return None
        offset, round_trip = min(self._samples, key=lambda s: s[1])
        return offset, max(1, (round_trip + 1) // 2)

    def clear(self) -> None:
        """Forgets all samples."""
        self._samples.clear()


class RunClock:
    """The current test run's time on the tester's clock.

    Time 0 is the event time of the run's ``dtron_start`` on the tester's clock; the clock reads this member's wall
    clock plus its offset estimate. It runs from ``dtron_start`` to ``dtron_stop`` (or until the tester leaves).
    """

    def __init__(self, wall_clock: Callable[[], int], offset: Callable[[], int]) -> None:
        self._wall = wall_clock
        self._offset = offset
        self._start_tester_ns = 0
        self._unit_us = 0
        self._run_id = ""
        self._generation = 0
        self._running = False
        self._changed = asyncio.Event()

    @property
    def running(self) -> bool:
        """Whether a run is under way."""
        return self._running

    @property
    def time_unit_us(self) -> int:
        """Microseconds per model time unit of the current (or last) run."""
        return self._unit_us

    @property
    def run_id(self) -> str:
        """The current (or last) run's id."""
        return self._run_id

    @property
    def generation(self) -> int:
        """Counts the runs started: a task of an earlier run can tell that its run is over."""
        return self._generation

    def start(self, tester_time_zero_ns: int, time_unit_us: int, run_id: str) -> None:
        """A run started at the tester's time ``tester_time_zero_ns``."""
        self._start_tester_ns = tester_time_zero_ns
        self._unit_us = max(1, time_unit_us)
        self._run_id = run_id
        self._generation += 1
        self._running = True
        self._wake()

    def stop(self) -> None:
        """The run is over."""
        self._running = False
        self._wake()

    def now_ns(self) -> int:
        """Nanoseconds of run time now (on the tester's clock)."""
        return self._wall() + self._offset() - self._start_tester_ns

    def now_units(self) -> float:
        """Model time units of run time now, in the current (or last) run's unit.

        :raises RuntimeError: if no run has started yet, so that there is no time unit
        """
        return self.now_ns() / self._unit_ns()

    def units_of(self, message: "object") -> float:
        """The run time, in units, of a message's event (its event time plus the offset its sender carried).

        :raises RuntimeError: if no run has started yet, so that there is no time unit
        """
        event = getattr(message, "event_time_ns") or getattr(message, "publish_time_ns")
        return (event + getattr(message, "clock_offset_ns") - self._start_tester_ns) / self._unit_ns()

    def _unit_ns(self) -> float:
        if self._unit_us <= 0:
            raise RuntimeError("no run has started yet: the run clock has no time unit (wait for dtron_start)")
        return self._unit_us * 1000.0

    async def sleep_until(self, units: float) -> bool:
        """Waits until run time ``units`` of the current run.

        :returns: True at that time, False if the run stopped or another started before
        """
        generation = self._generation
        while self._running and self._generation == generation:
            left_ns = units * self._unit_us * 1000.0 - self.now_ns()
            if left_ns <= 0:
                return True
            self._changed.clear()
            try:
                # wake early when the run changes; re-read the offset at least every 50 ms
                await asyncio.wait_for(self._changed.wait(), timeout=min(left_ns / 1e9, 0.05))
            except asyncio.TimeoutError:
                pass
        return False

    def _wake(self) -> None:
        self._changed.set()


def wall_clock_ns() -> int:
    """This host's wall clock, nanoseconds since the epoch."""
    return time.time_ns()


#: How far a tester's reading may lie outside a ping's round trip while the two clocks are still taken as one.
SAME_CLOCK_SLACK_NS = 1_000


def host_clock_id(boot_id: str = "/proc/sys/kernel/random/boot_id") -> str:
    """The id of the wall clock :func:`wall_clock_ns` reads: members with equal ids read one and the same clock (one
    running Linux kernel, named by its boot id), so their offset is 0; "" where it cannot be told."""
    try:
        with open(boot_id, encoding="ascii") as f:
            value = f.read().strip()
    except (OSError, ValueError):
        return ""
    return "linux-boot:" + value if value else ""


def same_clock(sent_ns: int, tester_ns: int, received_ns: int) -> bool:
    """Whether a ping's round trip agrees with the tester reading this member's clock: its reading lies within it."""
    return sent_ns - SAME_CLOCK_SLACK_NS <= tester_ns <= received_ns + SAME_CLOCK_SLACK_NS
