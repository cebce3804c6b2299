"""The run clock: before the first run there is no time unit, and asking for units says so instead of dividing by
zero; from a run's start on it counts in that run's unit, after the run's stop too."""

from __future__ import annotations

from types import SimpleNamespace

import pytest

from dtron import RunClock


def test_before_the_first_run_units_are_a_clear_error_and_then_the_runs() -> None:
    clock = RunClock(lambda: 5_000_000, lambda: 0)
    for ask in (clock.now_units, lambda: clock.units_of(SimpleNamespace(event_time_ns=2_000_000, clock_offset_ns=0))):
        with pytest.raises(RuntimeError, match="no run has started yet"):
            ask()
    clock.start(1_000_000, 1000, "run-1")
    assert clock.now_units() == 4.0
    assert clock.units_of(SimpleNamespace(event_time_ns=2_000_000, clock_offset_ns=0)) == 1.0
    clock.stop()
    assert clock.now_units() == 4.0  # in the last run's unit
