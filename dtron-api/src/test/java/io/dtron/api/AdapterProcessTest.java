package io.dtron.api;

import static org.junit.jupiter.api.Assertions.assertEquals;

import io.dtron.testadapter.EchoAdapterMain;
import io.dtron.testsupport.FreePorts;
import io.dtron.testsupport.Inbox;
import java.nio.file.Path;
import java.time.Duration;
import java.util.Map;
import java.util.concurrent.TimeUnit;
import org.junit.jupiter.api.Test;
import org.junit.jupiter.api.Timeout;
import org.junit.jupiter.api.io.TempDir;

/** The test JVM and an adapter in another JVM, which uses only io.dtron.api, exchange messages over TCP. */
@Timeout(value = 90, unit = TimeUnit.SECONDS)
class AdapterProcessTest {
    private final IDtronChannel move = IDtronChannel.of("move", "amount");
    private final IDtronChannel done = IDtronChannel.of("done", "amount");

    @Test
    void exchangesMessagesWithAnAdapterInAnotherJvm(@TempDir Path dir) throws Exception {
        String cluster = TestClusters.uniqueName("adapter");
        int port = FreePorts.range(FreePorts.BUS_RANGE);
        try (Dtron tester = Dtron.connect(DtronOptions.builder().clusterName(cluster).memberName("tester").port(port)
                .portRange(FreePorts.BUS_RANGE).build())) {
            Inbox ready = new Inbox(IDtronChannel.of("ready"));
            Inbox replies = new Inbox(done);
            tester.addDtronListener(ready);
            tester.addDtronListener(replies);
            try (ChildJvm adapter = ChildJvm.start(EchoAdapterMain.class, dir.resolve("adapter.log"), cluster,
                    Integer.toString(port))) {
                assertEquals("echo-adapter", ready.take().getSender(), adapter.output());

                for (int amount = 1; amount <= 50; amount++) {
                    tester.send(move.constructValued(Map.of("amount", amount)));
                }
                for (int amount = 1; amount <= 50; amount++) {
                    IDtronChannelValued reply = replies.take();
                    assertEquals(2 * amount, reply.getVariables().get("amount"));
                    assertEquals("echo-adapter", reply.getSender());
                }
                tester.send(IDtronChannel.of("quit").constructValued(Map.of()));
                assertEquals(0, adapter.waitFor(Duration.ofSeconds(30)), adapter.output());
            }
            assertEquals(51, tester.getStats().getPublished());
            assertEquals(0, tester.getStats().getRejectedTotal());
        }
    }
}
