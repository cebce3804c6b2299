package io.dtron.cli;

import static org.junit.jupiter.api.Assertions.assertEquals;
import static org.junit.jupiter.api.Assertions.assertTrue;

import io.dtron.bridge.BusRun;
import io.dtron.bridge.ChannelDelay;
import io.dtron.engine.ObservableWindow;
import io.dtron.model.ModelLoader;
import io.dtron.model.Network;
import io.dtron.model.TestInterface;
import io.dtron.testsupport.FreePorts;
import java.nio.file.Files;
import java.nio.file.Path;
import java.util.List;
import java.util.Optional;
import org.junit.jupiter.api.Test;
import org.junit.jupiter.api.io.TempDir;

/** What a bus run says about its timing before time 0: the automatic window and the narrow-window warning. */
class BusTimingTest {
    private static final Path TICKER = Path.of("../models/src/main/resources/io/dtron/models/ticker.xml");

    private static Optional<ObservableWindow> tickerWindow() throws Exception {
        Network network = ModelLoader.load(TICKER);
        return ObservableWindow.narrowest(network, TestInterface.fromNames(network));
    }

    @Test
    void theProbesBeforeTheRunSayHowManyRoundsAndWhyTheyStopped() {
        assertEquals("dtron run: probed the adapters in 14 rounds over 0.45 s while the engine warmed up, each probe an"
                + " input that reaches no listener, until their round trips were steady (the last rounds' round trips"
                + " up to 0.812 ms); each input is sent at least its adapters' round trip ahead of its time when they"
                + " hold inputs until then, else aimed that far inside the end of its window, or the 99th percentile"
                + " of its channel's delays once inputs are acknowledged",
                BusTiming.probingLine(new BusRun.Probing(14, true, 812, 450), true));
        assertTrue(BusTiming.probingLine(new BusRun.Probing(120, false, 31_000, 3_010), false).startsWith(
                "dtron run: probed the adapters in 120 rounds over 3.01 s, each probe an input that reaches no"
                        + " listener, until the limit, their round trips still uneven (the last rounds' round trips"
                        + " up to 31 ms)"));
        assertEquals("dtron run: no adapter on the bus to probe before the run",
                BusTiming.probingLine(new BusRun.Probing(0, false, 0, 0), true));
    }

    @Test
    void theAutomaticWindowCoversThreeTimesTheLongestDelayAndTwiceTheErrorWithAFloor() {
        assertEquals(BusRun.AUTO_WINDOW_FLOOR_MICROS,
                new BusRun.Delays(400_000, 50_000, 20, 1).autoWindowMicros());
        // 3 x 30 ms + 2 x 1.5 ms = 93 ms
        assertEquals(93_000, new BusRun.Delays(30_000_000, 1_500_000, 20, 1).autoWindowMicros());
        // rounded up to a whole millisecond
        assertEquals(91_000, new BusRun.Delays(30_000_000, 100_000, 20, 1).autoWindowMicros());
    }

    @Test
    void theTickersNarrowestWindowIsItsTickPeriod() throws Exception {
        ObservableWindow window = tickerWindow().orElseThrow();
        assertEquals("o_tick", window.channel());
        assertEquals(4, window.width(), window.toString());
    }

    @Test
    void delaysThatEatAFifthOfTheNarrowestWindowAreReportedWithATimeUnitThatFits() throws Exception {
        // 1 ms of delay against a window of 4 units: at 1000 us per unit it takes 25%
        BusRun.Delays delays = new BusRun.Delays(900_000, 100_000, 20, 1);
        String warning = BusTiming.windowWarning(tickerWindow(), delays, 1000).orElseThrow();
        assertTrue(warning.contains("the narrowest time window of an observable action, o_tick in Ticker (8 <= x <="
                + " 12, "), warning);
        assertTrue(warning.contains("is 4 time units = 4.000 ms at 1000 us per unit"), warning);
        assertTrue(warning.contains("take 25% of it"), warning);
        // 1 ms must be a tenth of 4 units: 2500 us, rounded up to 5000
        assertTrue(warning.endsWith("a time unit of 5000 us or more keeps them under 10%"), warning);
        // at 10 ms per unit the same delays take 2.5%: nothing to say
        assertEquals(Optional.empty(), BusTiming.windowWarning(tickerWindow(), delays, 10_000));
    }

    @Test
    void aRunAgainstTheDeltaExtendedModelWidensItsBoundsFirst() throws Exception {
        Path report = Path.of(BusTimingTest.class.getResource("delta-report.json").toURI());
        CommandRun r = CommandRun.of(TICKER.toString(), "--cluster", "widened-" + System.nanoTime(), "--port",
                Integer.toString(FreePorts.range(FreePorts.BUS_RANGE)), "--port-range",
                Integer.toString(FreePorts.BUS_RANGE), "--adapter", io.dtron.testadapter.RunClockTicker.class.getName(),
                "--timeunit", "10000", "--timeout", "60",
                "--delay-policy", "eager", "--delta-from", report.toString());
        // 2.4 ms + 1.75 ms at 10 ms per unit: the invariant x <= P + T grows by one unit; the lower bounds would grow
        // by 0.27 ms, rounded down to nothing
        assertTrue(r.out().contains("dtron run: testing against the Delta-extended model: 1 clock bound widened by"
                + " the delays of "), r.out());
        assertTrue(r.out().contains("statistics: "), "the run went on: " + r.out());
        CommandRun missing = CommandRun.of(TICKER.toString(), "--delta-from", "no-such-report.json");
        assertEquals(1, missing.exit(), missing.out() + missing.err());
        assertTrue(missing.err().startsWith("dtron run: --delta-from no-such-report.json: "), missing.err());
    }

    @Test
    void niceNumbersAreOneTwoOrFiveTimesAPowerOfTen() {
        assertEquals(1, BusTiming.niceCeil(0.3));
        assertEquals(2, BusTiming.niceCeil(1.5));
        assertEquals(5000, BusTiming.niceCeil(2500));
        assertEquals(10_000, BusTiming.niceCeil(5001));
    }

    @Test
    void theDeltaReportIsJsonWithOneEntryPerChannelAndDirection() {
        String json = BusTiming.deltaReport(Path.of("m.xml"), 10_000, "ab12", List.of(
                new ChannelDelay("reset", "input", 11, 180, 2400), new ChannelDelay("tick", "output", 24, 90, 1750)));
        assertEquals("""
                {
                  "model": "m.xml",
                  "timeUnitMicros": 10000,
                  "runId": "ab12",
                  "channels": [
                    {"channel": "reset", "direction": "input", "count": 11, "lowMicros": 180, "highMicros": 2400},
                    {"channel": "tick", "direction": "output", "count": 24, "lowMicros": 90, "highMicros": 1750}
                  ]
                }
                """, json);
    }

    @Test
    void aRunOnTheBusSaysWhatItMeasuredAndWhatTheRunSaw(@TempDir Path dir) throws Exception {
        Path report = dir.resolve("delta.json");
        CommandRun r = CommandRun.of(TICKER.toString(), "--cluster", "timing-" + System.nanoTime(), "--port",
                Integer.toString(FreePorts.range(FreePorts.BUS_RANGE)), "--port-range",
                Integer.toString(FreePorts.BUS_RANGE), "--adapter", io.dtron.testadapter.RunClockTicker.class.getName(),
                "--timeunit", "100", "--timeout", "300",
                "--delay-policy", "eager", "--delta-report", report.toString());
        assertTrue(r.out().contains("dtron run: delays on the bus before the run: up to "), r.out());
        assertTrue(r.out().matches("(?s).*reorder window \\(Delta\\) [0-9.]+ ms \\(auto: .*"), r.out());
        assertTrue(r.out().contains("dtron run: warning: the narrowest time window of an observable action, o_tick in"
                + " Ticker (8 <= x <= 12, "), r.out());
        assertTrue(r.out().contains("is 4 time units = 0.400 ms at 100 us per unit"), r.out());
        assertTrue(r.out().contains("reorder window (Delta): "), r.out());
        String json = Files.readString(report);
        assertTrue(json.contains("\"timeUnitMicros\": 100,"), json);
        assertTrue(json.contains("\"channels\": ["), json);
    }
}
