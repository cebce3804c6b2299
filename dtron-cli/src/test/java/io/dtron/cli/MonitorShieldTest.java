package io.dtron.cli;

import static io.dtron.cli.MonitorOnBus.REQ;
import static io.dtron.cli.MonitorOnBus.RESP;
import static org.junit.jupiter.api.Assertions.assertEquals;
import static org.junit.jupiter.api.Assertions.assertTrue;

import io.dtron.api.Dtron;
import io.dtron.api.DtronListener;
import io.dtron.api.DtronOptions;
import io.dtron.api.IDtronChannel;
import io.dtron.api.IDtronChannelValued;
import io.dtron.testsupport.Waits;
import java.io.PrintWriter;
import java.io.StringWriter;
import java.net.InetAddress;
import java.nio.file.Files;
import java.nio.file.Path;
import java.util.List;
import java.util.Map;
import java.util.UUID;
import java.util.concurrent.CompletableFuture;
import java.util.concurrent.CopyOnWriteArrayList;
import java.util.concurrent.TimeUnit;
import org.junit.jupiter.api.Test;
import org.junit.jupiter.api.Timeout;
import org.junit.jupiter.api.io.TempDir;

/**
 * {@code dtron monitor --cluster NAME --shield resp} between a producer of the monitor tests' server model and a
 * consumer, real JGroups members on loopback: the response the model forbids (before the server's 1 time unit) is
 * withheld, which the alarm on {@code dtron_alarm} says, and the allowed one is republished on {@code
 * resp_shielded}, where the consumer listens. The producer stamps its events' times, and a run's start ends the
 * watch once the shield has passed one and withheld the other, so load changes nothing.
 */
@Timeout(value = 2, unit = TimeUnit.MINUTES)
class MonitorShieldTest {

    @Test
    void theShieldWithholdsTheForbiddenResponseAndPassesTheAllowedOne(@TempDir Path dir) throws Exception {
        Path model = dir.resolve("server.xta");
        Files.copy(MonitorCommandTest.SERVER, model);
        String cluster = "shield-" + UUID.randomUUID().toString().substring(0, 8);
        DtronOptions.Builder options = DtronOptions.builder().clusterName(cluster)
                .bindAddress(InetAddress.getLoopbackAddress());
        List<IDtronChannelValued> shielded = new CopyOnWriteArrayList<>();
        List<IDtronChannelValued> alarms = new CopyOnWriteArrayList<>();
        try (Dtron consumer = Dtron.connect(options.build()); Dtron producer = Dtron.connect(options.build())) {
            consumer.addDtronListener(new DtronListener(IDtronChannel.of("resp_shielded", "n")) {
                @Override
                public void messageReceived(IDtronChannelValued message) {
                    shielded.add(message);
                }
            });
            consumer.addDtronListener(new DtronListener(Dtron.ALARM) {
                @Override
                public void messageReceived(IDtronChannelValued message) {
                    alarms.add(message);
                }
            });
            StringWriter out = new StringWriter();
            StringWriter err = new StringWriter();
            CompletableFuture<Integer> exit = CompletableFuture.supplyAsync(() -> DtronCommand.run(new String[] {
                "monitor", model.toString(), "--cluster", cluster, "--timeunit", "100000", "--shield", "resp",
                "--duration", "60"}, new PrintWriter(out, true), new PrintWriter(err, true)));
            Waits.await("the shield on the bus").until(() -> out.toString().contains(" as ") || exit.isDone());
            Waits.await("the shield among the members").until(() -> producer.getMembers().size() == 3);
            // the server's times, 100 ms per unit: a request, a response 10 ms later (the model: 1 to 3 units), one
            // 150 ms later
            long t0 = producer.currentTimeNanos();
            producer.send(REQ.constructValued(Map.of("n", 1)), t0);
            IDtronChannelValued early = producer.send(RESP.constructValued(Map.of("n", 2)), t0 + 10_000_000L);
            producer.send(RESP.constructValued(Map.of("n", 2)), t0 + 150_000_000L);
            // the shield judges its channel's messages as they come: once it passed one and withheld the other, a
            // run's start ends the watch of the running system (and the monitor, which follows one run), whatever
            // the load made of the times between
            Waits.await("the allowed response passed and the alarm of the other").until(() -> shielded.size() == 1
                    && !alarms.isEmpty() || exit.isDone());
            producer.send(Dtron.RUN_START.constructValued(Map.of("timeunit", 100_000)), producer.currentTimeNanos());
            assertEquals(2, exit.get(1, TimeUnit.MINUTES), out + "\n" + err);
            String printed = out.toString();
            assertTrue(printed.contains("violation 1 at t=") && printed.contains("resp(n=2) at t=")
                    && printed.contains("is not allowed then") && printed.contains("withheld: not republished on"
                    + " resp_shielded"), printed);
            assertTrue(printed.contains("dtron monitor: 1 run, 1 violation (the watch: 1), 3 events checked, 0 too late"
                    + " to judge, 1 withheld"), printed);
            // the shield's messages in its order: the allowed response, the alarm and the verdict
            Waits.await("the verdict on dtron_alarm").until(() -> alarms.stream()
                    .anyMatch(a -> a.getVariables().get("verdict") == 1));
            assertEquals(1, shielded.size(), shielded.toString());
            assertEquals(Map.of("n", 2), shielded.get(0).getVariables());
            IDtronChannelValued alarm = alarms.get(0);
            assertEquals(Map.of("number", 1, "reason", 1, "channel", 2, "sequence", (int) early.getSequence(),
                    "withheld", 1, "verdict", 0), alarm.getVariables());
            assertEquals(Map.of("number", 1, "reason", 1, "channel", 0, "sequence", 0, "withheld", 0, "verdict", 1),
                    alarms.get(1).getVariables());
        }
    }
}
