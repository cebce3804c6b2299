"""Channel templates and the clock-offset estimator, without a bus."""

import pytest

import dtron


def test_a_channel_checks_its_names_and_its_values() -> None:
    tick = dtron.Channel("tick", "seq")
    assert tick.value(seq=3).variables == {"seq": 3}
    with pytest.raises(dtron.InvalidMessage) as unknown:
        tick.value(seq=1, other=2)
    assert unknown.value.reason == "UNKNOWN_VARIABLES"
    with pytest.raises(dtron.InvalidMessage) as missing:
        tick.value()
    assert missing.value.reason == "MISSING_VARIABLES"
    with pytest.raises(ValueError):
        tick.value(seq=2**31)
    with pytest.raises(ValueError):
        dtron.Channel("1tick")
    with pytest.raises(ValueError):
        dtron.Channel("tick", "a b")
    with pytest.raises(ValueError):
        dtron.Channel("tick", "seq", "seq")


def test_the_estimate_is_the_sample_with_the_shortest_round_trip() -> None:
    estimator = dtron.OffsetEstimator()
    assert estimator.estimate() is None
    # tester 50 ms ahead; round trips of 10 ms and 2 ms
    assert estimator.add(0, 55_000_000, 10_000_000) == (50_000_000, 5_000_000)
    assert estimator.add(100_000_000, 151_000_000, 102_000_000) == (50_000_000, 1_000_000)
    assert estimator.add(200_000_000, 262_000_000, 220_000_000) == (50_000_000, 1_000_000)
    assert estimator.add(300_000_000, 0, 290_000_000) == (50_000_000, 1_000_000), "a negative round trip is ignored"


def test_the_host_clock_is_named_by_the_boot_id_and_checked_by_round_trips(tmp_path) -> None:
    boot = tmp_path / "boot_id"
    boot.write_text("0a1b-2c\n")
    assert dtron.clock.host_clock_id(str(boot)) == "linux-boot:0a1b-2c"
    boot.write_text("\n")
    assert dtron.clock.host_clock_id(str(boot)) == ""
    assert dtron.clock.host_clock_id(str(tmp_path / "none")) == ""
    # the tester's reading within the round trip (a microsecond of slack either side), or not
    assert dtron.clock.same_clock(1_000_000, 1_500_000, 2_000_000)
    assert dtron.clock.same_clock(1_000_000, 999_000, 2_000_000)
    assert not dtron.clock.same_clock(1_000_000, 998_999, 2_000_000)
    assert not dtron.clock.same_clock(1_000_000, 2_001_001, 2_000_000)
