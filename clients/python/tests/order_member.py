"""One member of the cross-language total-order test (DTRON's OrderMemberMain in Python).

Arguments: NATS URL, bus, member id, output file, messages to publish, number of members. Waits until it heard every
member say ready (answering newcomers), publishes order(n) for n = 1..messages, records "sender n sequence" of every
order message in receive order, writes them to the output file, says finished and waits for everyone's. Exit 0 if
it received all messages of all members, 2 if the members did not meet, 3 if messages went missing.
"""

from __future__ import annotations

import asyncio
import sys
import time

import dtron

ORDER = dtron.Channel("order", "n")
READY = dtron.Channel("ready")
FINISHED = dtron.Channel("finished")


async def until(condition, seconds: float) -> bool:
    deadline = time.monotonic() + seconds
    while not condition():
        if time.monotonic() > deadline:
            return False
        await asyncio.sleep(0.01)
    return True


async def main(url: str, bus_name: str, name: str, out: str, messages: int, members: int) -> int:
    received: list[str] = []
    ready: set[str] = set()
    finished: set[str] = set()
    async with await dtron.connect(url, bus=bus_name, member=name) as bus:
        bus.add_listener(ORDER, lambda m: received.append(f"{m.sender} {m.variables['n']} {m.sequence}"))

        async def on_ready(message: dtron.Message) -> None:
            if message.sender not in ready:
                ready.add(message.sender)
                if message.sender != name:
                    await bus.send(READY.value())  # answer a newcomer, which may have missed this member's

        bus.add_listener(READY, on_ready)
        bus.add_listener(FINISHED, lambda m: finished.add(m.sender))
        if not await until(lambda: len(bus.members) >= members, 60):
            print(f"{name}: members {bus.members}", file=sys.stderr)
            return 2
        await bus.send(READY.value())
        if not await until(lambda: len(ready) >= members, 60):
            print(f"{name}: heard only {ready}", file=sys.stderr)
            return 2
        for n in range(1, messages + 1):
            await bus.send(ORDER.value(n=n))
        complete = await until(lambda: len(received) >= messages * members, 90)
        with open(out, "w") as file:
            file.write("".join(line + "\n" for line in received))
        await bus.send(FINISHED.value())
        # the others may take long to catch up (a member that lost its server and reconnected, on a loaded
        # machine): wait for them as long as the tests wait for the slowest member (150 s)
        done = await until(lambda: len(finished) >= members, 150)
        if not complete or not done:
            print(f"{name}: received {len(received)}, finished {finished}", file=sys.stderr)
            return 3
    return 0


if __name__ == "__main__":
    u, b, m, o, count, size = sys.argv[1:7]
    sys.exit(asyncio.run(main(u, b, m, o, int(count), int(size))))
