"""DTRON's Python client: adapters that connect a system under test to DTRON over a NATS bus.

Members of a bus hold its secret, by default the key file ``~/.dtron/bus.key`` made on first use (see
:func:`connect`).

>>> import asyncio, dtron
>>> reset = dtron.Channel("reset")           # the model's i_reset
>>> tick = dtron.Channel("tick", "seq")      # the model's o_tick with o_tick_seq
>>> async def main():
...     async with await dtron.connect("nats://127.0.0.1:4222", bus="ticker") as bus:
...         bus.declare_outputs(tick)
...         @bus.listener(reset)
...         def on_reset(message: dtron.Message) -> None: ...
...         await bus.send(tick.value(seq=1))
"""

from dtron.bus import RUN_START, RUN_STOP, Bus, Stats, connect
from dtron.channel import RESERVED, Channel, InvalidMessage, Message
from dtron.clock import ClockOffset, OffsetEstimator, RunClock
from dtron.secret import KeyFileError, default_key_file

__all__ = ["Bus", "Channel", "ClockOffset", "InvalidMessage", "KeyFileError", "Message", "OffsetEstimator", "RESERVED",
           "RUN_START", "RUN_STOP", "RunClock", "Stats", "connect", "default_key_file"]
