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
 * Bad input from a client in another language: a Python program publishes, with plain nats-py, bytes that are no
 * Sync, a Sync on a channel the Java member does not know, and Syncs with unknown and missing variables, then a good
 * one. The Java member rejects and counts each as on JGroups, and delivers the good one.
 */
@Timeout(value = 2, unit = TimeUnit.MINUTES)
class NatsBadInputTest {
    private static final IDtronChannel ORDER = IDtronChannel.of("order", "n");

    /** The Python side: argv[1] the server, argv[2] the bus. */
    private static final String ROGUE = """
            import asyncio, sys
            import nats
            from dtron._proto.Sync_pb2 import Sync

            def sync(name, **variables):
                message = Sync(name=name, sender="rogue", sequence=1)
                for key, value in variables.items():
                    message.variables.add(name=key, value=value)
                return message.SerializeToString()

            async def main(url, bus):
                nc = await nats.connect(url)
                js = nc.jetstream()
                for channel, payload in [("order", b"\\xff\\x01\\x02"), ("nosuch", sync("nosuch")),
                                         ("order", sync("order", n=1, m=2)), ("order", sync("order")),
                                         ("order", sync("order", n=7))]:
                    await js.publish(f"dtron.{bus}.c.{channel}", payload, headers={"Dtron-Sender": "rogue"})
                await nc.close()

            asyncio.run(main(sys.argv[1], sys.argv[2]))
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
                    .channels(List.of(ORDER)).build())) {
                Inbox inbox = new Inbox(ORDER);
                tester.addDtronListener(inbox);
                Process process = new ProcessBuilder(python, rogue.toString(), server.url(), bus)
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
