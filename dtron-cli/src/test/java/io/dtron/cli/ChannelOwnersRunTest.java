package io.dtron.cli;

import static org.junit.jupiter.api.Assertions.assertEquals;
import static org.junit.jupiter.api.Assertions.assertFalse;
import static org.junit.jupiter.api.Assertions.assertTrue;

import io.dtron.api.ChildJvm;
import io.dtron.api.Dtron;
import io.dtron.api.DtronListener;
import io.dtron.api.DtronOptions;
import io.dtron.api.IDtronChannelValued;
import io.dtron.testadapter.TickerAdapterMain;
import io.dtron.testsupport.DocPage;
import io.dtron.testsupport.NatsServer;
import io.dtron.testsupport.TickerRunBounds;
import io.dtron.testsupport.Waits;
import java.nio.file.Path;
import java.util.ArrayList;
import java.util.Collections;
import java.util.List;
import java.util.UUID;
import java.util.concurrent.CompletableFuture;
import java.util.concurrent.TimeUnit;
import java.util.regex.Matcher;
import java.util.regex.Pattern;
import org.junit.jupiter.api.Test;
import org.junit.jupiter.api.Timeout;
import org.junit.jupiter.api.io.TempDir;

/**
 * Each output of the model has one owner on the bus, with adapters in JVMs of their own: two ticker adapters that
 * both send {@code tick} are named and the run is refused (they were there before the start) or ends INCONCLUSIVE
 * (the second joined during the run), never judged as one ticker; members that serve no channel of the run (an
 * observer, a refused second tester) come and go and the run passes. The tester runs in this JVM, as {@code dtron
 * run} on the bundled ticker model at 100 ms per time unit (the model's 2 units of jitter hold for a fresh adapter
 * JVM on a busy machine).
 */
@Timeout(value = 3, unit = TimeUnit.MINUTES)
class ChannelOwnersRunTest {
    private static final String TICKER = Path.of("..", "models", "src", "main", "resources", "io", "dtron", "models",
            "ticker.xml").toString();
    private static final String TICK_OWNERS = "output tick is sent by 2 members, ticker-a (receives [reset], sends"
            + " [tick]) and ticker-b (receives [reset], sends [tick])";
    /** {@link #TICK_OWNERS} as a run names them when ticker b joins during it. */
    private static final Pattern JOINED_TICK_OWNERS = Pattern.compile(Pattern.quote("INCONCLUSIVE: output tick is sent"
            + " by 2 members, ticker-a (receives [reset], sends [tick]) and ticker-b (receives [") + "(reset)?"
            + Pattern.quote("], sends [tick])"));

    @TempDir
    Path dir;

    private final String cluster = "owners-" + UUID.randomUUID().toString().substring(0, 8);

    private ChildJvm ticker(String name, String... nats) throws Exception {
        List<String> args = new ArrayList<>(List.of(cluster, name, "correct", "1"));
        args.addAll(List.of(nats));
        ChildJvm jvm = ChildJvm.start(TickerAdapterMain.class, dir.resolve(name + ".log"), args.toArray(new String[0]));
        try {
            jvm.awaitOutput("joined", Waits.TIMEOUT);
        } catch (Throwable e) {
            jvm.close();
            throw e;
        }
        return jvm;
    }

    private String[] run(int timeoutUnits, String... more) {
        return run(100_000, timeoutUnits, more);
    }

    private String[] run(int unitMicros, int timeoutUnits, String... more) {
        List<String> args = new ArrayList<>(List.of(TICKER, "--cluster", cluster, "--timeunit",
                String.valueOf(unitMicros), "--timeout", String.valueOf(timeoutUnits), "--delay-policy", "eager",
                "--seed", "1"));
        args.addAll(List.of(more));
        return args.toArray(new String[0]);
    }

    @Test
    void twoAdaptersSendingOneOutputBeforeTheStartAreNamedAndTheRunIsRefused() throws Exception {
        try (ChildJvm a = ticker("ticker-a");
                ChildJvm b = ticker("ticker-b")) {
            CommandRun r = CommandRun.of(run(100));
            assertRefused(r, "127.0.0.1");
        }
    }

    @Test
    void twoAdaptersSendingOneOutputOnNatsAreNamedAndTheRunIsRefused() throws Exception {
        try (NatsServer nats = NatsServer.start(dir);
                ChildJvm a = ticker("ticker-a", nats.url());
                ChildJvm b = ticker("ticker-b", nats.url())) {
            CommandRun r = CommandRun.of(run(100, "--bus", nats.url()));
            assertRefused(r, nats.url());
        }
    }

    /** The refusal is the one line adapters.md shows, on this test's bus. */
    private void assertRefused(CommandRun r, String where) throws Exception {
        assertEquals(1, r.exit(), r.out() + r.err());
        String shown = DocPage.read("adapters.md").blockAfter("naming them and what they serve, with exit code 1:")
                .code().strip();
        assertTrue(shown.contains(TICK_OWNERS), shown);
        assertEquals(shown.replace("bus 'lab' at 127.0.0.1:", "bus '" + cluster + "' at " + where + ":"),
                r.err().strip());
        assertFalse(r.out().contains("PASSED") || r.out().contains("FAILED"), "no run: " + r.out());
    }

    @Test
    void aSecondAdapterSendingTheOutputThatJoinsDuringTheRunEndsItInconclusiveNamingIt() throws Exception {
        secondAdapterJoinsDuringTheRun();
    }

    @Test
    void aSecondAdapterSendingTheOutputThatJoinsDuringTheRunOnNatsEndsItInconclusiveNamingIt() throws Exception {
        try (NatsServer nats = NatsServer.start(dir)) {
            secondAdapterJoinsDuringTheRun("--bus", nats.url());
        }
    }

    /** Ticker b joins once a run against ticker a started: INCONCLUSIVE naming both, never FAILED. */
    private void secondAdapterJoinsDuringTheRun(String... bus) throws Exception {
        String[] nats = bus.length == 0 ? new String[0] : new String[] {bus[1]};
        try (ChildJvm a = ticker("ticker-a", nats);
                Watcher watcher = new Watcher(cluster, nats)) {
            // 60 s of test time: the second adapter's JVM joins within it, however busy the machine
            CompletableFuture<CommandRun> first = CompletableFuture.supplyAsync(() -> CommandRun.of(run(600, bus)));
            Waits.await("the run's start").until(() -> watcher.saw("start"));
            try (ChildJvm b = ticker("ticker-b", nats)) {
                CommandRun r = first.get(2, TimeUnit.MINUTES);
                assertEquals(3, r.exit(), r.out() + r.err());
                // named at the first tick after it said it sends tick, whichever ticker sent it: never judged;
                // ticker b, joining, may not yet have said that it receives reset then
                assertTrue(JOINED_TICK_OWNERS.matcher(r.out()).find(), r.out());
                assertFalse(r.out().contains("FAILED"), r.out());
            }
        }
    }

    @Test
    void membersThatServeNoChannelOfTheRunComeAndGoAndItPasses() throws Exception {
        try (ChildJvm bystander = ChildJvm.start(BystanderMain.class, dir.resolve("bystander.log"), cluster,
                "bystander");
                ChildJvm a = ticker("ticker-a");
                Watcher watcher = new Watcher(cluster)) {
            bystander.awaitOutput("joined", Waits.TIMEOUT);
            // half a second per unit: the model's 2 units of jitter, 1 s, hold for a ticker JVM held up by a loaded
            // machine (at 100 ms one was seen to tick 1.2 s late there, with two more JVMs and a second tester)
            CompletableFuture<CommandRun> first = CompletableFuture.supplyAsync(() -> CommandRun.of(run(500_000,
                    40)));
            Waits.await("the run's start").until(() -> watcher.saw("start"));
            // a second tester of the same model joins, is refused, and leaves
            CommandRun second = CommandRun.of(run(500_000, 40));
            assertEquals(1, second.exit(), second.out() + second.err());
            assertTrue(second.err().contains("has a run in progress"), second.err());
            Matcher id = Pattern.compile(" as (\\S+), seed").matcher(second.out());
            assertTrue(id.find(), second.out());
            // the observer that was there before the start leaves (its process dies)
            bystander.kill();
            Waits.await("the bystander gone").until(() -> watcher.saw("left bystander"));
            CommandRun r = first.get(2, TimeUnit.MINUTES);
            assertFalse(r.out().contains("left the bus") || r.out().contains("bystander (")
                    || r.out().contains(id.group(1) + " ("), "neither ended the run: " + r.out());
            // PASSED, unless the loaded machine held the ticker's JVM up past the 1 s (which its log says) or the tester
            TickerRunBounds.assertPassedUnlessHeldUp(r.exit(), r.out() + r.err(), 40, a::output);
            // both left while the run went on
            Waits.await("the run's stop").until(() -> watcher.saw("stop"));
            assertTrue(watcher.before("left " + id.group(1), "stop"), watcher.events().toString());
            assertTrue(watcher.before("left bystander", "stop"), watcher.events().toString());
        }
    }

    /** A member of the test's own that notes the run's start and stop and who left, in the bus's order. */
    private static final class Watcher implements AutoCloseable {
        private final Dtron dtron;
        private final List<String> events = Collections.synchronizedList(new ArrayList<>());

        /** Joins the JGroups bus {@code cluster}, or the NATS bus of that name at the server {@code nats} names. */
        Watcher(String cluster, String... nats) {
            DtronOptions.Builder options = DtronOptions.builder().clusterName(cluster).memberName("watcher");
            if (nats.length > 0) {
                options.natsServers(List.of(nats));
            }
            dtron = Dtron.connect(options.build());
            dtron.addDtronListener(new DtronListener(Dtron.RUN_START) {
                @Override
                public void messageReceived(IDtronChannelValued message) {
                    events.add("start");
                }
            });
            dtron.addDtronListener(new DtronListener(Dtron.RUN_STOP) {
                @Override
                public void messageReceived(IDtronChannelValued message) {
                    events.add("stop");
                }
            });
            dtron.addMembershipListener((members, joined, left) -> left.forEach(m -> events.add("left " + m)));
        }

        boolean saw(String event) {
            return events.contains(event);
        }

        boolean before(String event, String later) {
            synchronized (events) {
                int at = events.indexOf(event);
                return at >= 0 && (events.indexOf(later) < 0 || at < events.indexOf(later));
            }
        }

        List<String> events() {
            synchronized (events) {
                return List.copyOf(events);
            }
        }

        @Override
        public void close() {
            dtron.close();
        }
    }
}
