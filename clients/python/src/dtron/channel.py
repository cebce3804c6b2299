"""Channel templates and the messages that travel on them."""

from __future__ import annotations

import re
from dataclasses import dataclass, field
from typing import Mapping

#: DTRON's own channels: no model channel may have these names.
RESERVED = frozenset(
    {"dtron_start", "dtron_stop", "dtron_ack", "dtron_hello", "dtron_ping", "dtron_pong", "dtron_serve",
     "dtron_verdict", "dtron_model", "dtron_model_outcome", "dtron_alarm"}
)

_NAME = re.compile(r"[A-Za-z_][A-Za-z0-9_]*\Z")


class InvalidMessage(ValueError):
    """A message that does not fit its channel: unknown or missing variables, or no valid Sync at all."""

    def __init__(self, reason: str, detail: str) -> None:
        super().__init__(f"{reason}: {detail}")
        #: MALFORMED, UNKNOWN_CHANNEL, UNKNOWN_VARIABLES or MISSING_VARIABLES, as the Java API counts them.
        self.reason = reason


@dataclass(frozen=True)
class Channel:
    """A channel template: its name (a model channel without its i_/o_ prefix) and the names of its variables.

    ``Channel("tick", "seq")`` is the model's ``o_tick`` with the global ``o_tick_seq`` attached.
    """

    name: str
    variables: tuple[str, ...] = ()

    def __init__(self, name: str, *variables: str) -> None:
        if not _NAME.match(name):
            raise ValueError(f"channel name {name!r} is no identifier")
        for variable in variables:
            if not _NAME.match(variable):
                raise ValueError(f"variable name {variable!r} of channel {name!r} is no identifier")
        if len(set(variables)) != len(variables):
            raise ValueError(f"channel {name!r} names a variable twice: {variables}")
        object.__setattr__(self, "name", name)
        object.__setattr__(self, "variables", tuple(variables))

    def check(self, names: set[str] | frozenset[str]) -> None:
        """Raises :class:`InvalidMessage` unless ``names`` are exactly this channel's variables."""
        unknown = sorted(set(names) - set(self.variables))
        if unknown:
            raise InvalidMessage("UNKNOWN_VARIABLES", f"channel {self.name} has no variable {', '.join(unknown)}"
                                 f" (variables: {list(self.variables)})")
        missing = [v for v in self.variables if v not in names]
        if missing:
            raise InvalidMessage("MISSING_VARIABLES", f"channel {self.name} lacks variable {', '.join(missing)}")

    def value(self, **variables: int) -> "Message":
        """A message on this channel with these variable values, to send.

        :raises InvalidMessage: if the variables are not exactly the channel's
        :raises ValueError: if a value is no 32-bit integer
        """
        self.check(frozenset(variables))
        for name, number in variables.items():
            if not isinstance(number, int) or not -(2**31) <= number < 2**31:
                raise ValueError(f"variable {name} of channel {self.name} must be a 32-bit int, not {number!r}")
        return Message(self, {v: variables[v] for v in self.variables})


@dataclass(frozen=True)
class Message:
    """A message: on a channel, with its variables and, once on the bus, its stamp.

    Times are nanoseconds since the epoch on the sender's wall clock; ``clock_offset_ns`` is the sender's estimate of
    (tester's clock - its clock), so that ``event_time_ns + clock_offset_ns`` is the event on the tester's clock.
    """

    channel: Channel
    variables: Mapping[str, int] = field(default_factory=dict)
    sender: str = ""
    sequence: int = 0
    publish_time_ns: int = 0
    event_time_ns: int = 0
    run_id: str = ""
    clock_offset_ns: int = 0
    clock_error_ns: int = 0
    receive_time_ns: int = 0

    @property
    def name(self) -> str:
        """The channel's name."""
        return self.channel.name
