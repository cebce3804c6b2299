package io.dtron.models.ticker;

import static org.junit.jupiter.api.Assertions.assertEquals;
import static org.junit.jupiter.api.Assertions.assertTrue;

import io.dtron.api.Dtron;
import io.dtron.api.DtronOptions;
import io.dtron.api.DtronStats;
import io.dtron.api.IDtronChannel;
import io.dtron.api.IDtronChannelValued;
import io.dtron.api.InvalidMessageException.Reason;
import io.dtron.testsupport.Inbox;
import io.dtron.testsupport.NatsServer;
import java.nio.file.Files;
import java.nio.file.Path;
import java.util.List;
import java.util.concurrent.TimeUnit;
import org.junit.jupiter.api.Test;
import org.junit.jupiter.api.Timeout;
import org.junit.jupiter.api.io.TempDir;

/**
 * Bad input from a client in another language: a Python program holding the bus's secret publishes, with plain
 * nats-py and its own message codes (security.md, made here with Python's hmac), bytes that are no Sync, a Sync on a
 * channel the Java member does not know, and Syncs with unknown and missing variables, then a good one. The Java
 * member rejects and counts each as on JGroups, and delivers the good one.
 */
@Timeout(value = 2, unit = TimeUnit.MINUTES)
class NatsBadInputTest {
    private static final IDtronChannel ORDER = IDtronChannel.of("order", "n");

    private static final String SECRET = "0123456789abcdef0123456789abcdef0123456789abcdef0123456789abcdef";

    /** The Python side: argv[1] the server, argv[2] the bus, argv[3] the bus's secret. */
    private static final String ROGUE = """
            import asyncio, hashlib, hmac, struct, sys, time
            import nats
            from dtron._proto.Sync_pb2 import Sync

            def signed(secret, subject, sender, seq, data):
                key = hmac.new(secret.encode(), b"dtron-bus-mac-v1", hashlib.sha256).digest()
                now = str(time.time_ns())
                items = [x.encode() for x in (subject, sender, str(seq), now, "", "")] + [data]
                m = b"".join(struct.pack(">I", len(x)) + x for x in items)
                return {"Dtron-Sender": sender, "Dtron-Seq": str(seq), "Dtron-Time": now,
                        "Dtron-Mac": hmac.new(key, m, hashlib.sha256).hexdigest()}

            def sync(name, **variables):
                message = Sync(name=name, sender="rogue", sequence=1)
                for key, value in variables.items():
                    message.variables.add(name=key, value=value)
                return message.SerializeToString()

            async def main(url, bus, secret):
                nc = await nats.connect(url)
                js = nc.jetstream()
                messages = [("order", b"\\xff\\x01\\x02"), ("nosuch", sync("nosuch")),
                            ("order", sync("order", n=1, m=2)), ("order", sync("order")),
                            ("order", sync("order", n=7))]
                for seq, (channel, payload) in enumerate(messages, start=1):
                    subject = f"dtron.{bus}.c.{channel}"
                    await js.publish(subject, payload, headers=signed(secret, subject, "rogue", seq, payload))
                await nc.close()

            asyncio.run(main(sys.argv[1], sys.argv[2], sys.argv[3]))
            """;

    @TempDir
    Path dir;

    @Test
    void badInputFromPythonIsRejectedAndCountedAndTheRestDelivered() throws Exception {
        String python = NatsClients.python();
        Path rogue = Files.writeString(dir.resolve("rogue.py"), ROGUE);
        try (NatsServer server = NatsServer.start(dir)) {
            String bus = NatsTickerTest.cluster("bad");
            try (Dtron tester = Dtron.connect(DtronOptions.builder().clusterName(bus).natsServers(server.url())
                    .secret(SECRET).channels(List.of(ORDER)).build())) {
                Inbox inbox = new Inbox(ORDER);
                tester.addDtronListener(inbox);
                Process process = new ProcessBuilder(python, rogue.toString(), server.url(), bus, SECRET)
                        .redirectErrorStream(true).redirectOutput(dir.resolve("rogue.log").toFile()).start();
                assertTrue(process.waitFor(60, TimeUnit.SECONDS), "rogue still running");
                assertEquals(0, process.exitValue(), Files.readString(dir.resolve("rogue.log")));
                IDtronChannelValued good = inbox.take();
                assertEquals(7, good.getVariables().get("n"));
                assertEquals("rogue", good.getSender());
                DtronStats stats = tester.getStats();
                assertEquals(1, stats.getRejected(Reason.MALFORMED), stats.toString());
                assertEquals(1, stats.getRejected(Reason.UNKNOWN_CHANNEL), stats.toString());
                assertEquals(1, stats.getRejected(Reason.UNKNOWN_VARIABLES), stats.toString());
                assertEquals(1, stats.getRejected(Reason.MISSING_VARIABLES), stats.toString());
                assertEquals(1, stats.getAccepted(), stats.toString());
            }
        }
    }
}
