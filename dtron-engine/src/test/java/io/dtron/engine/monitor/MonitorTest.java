package io.dtron.engine.monitor;

import static org.junit.jupiter.api.Assertions.assertEquals;
import static org.junit.jupiter.api.Assertions.assertNotNull;
import static org.junit.jupiter.api.Assertions.assertNull;
import static org.junit.jupiter.api.Assertions.assertThrows;
import static org.junit.jupiter.api.Assertions.assertTrue;

import io.dtron.engine.DelayPolicy;
import io.dtron.engine.Event;
import io.dtron.engine.OnlineTester;
import io.dtron.engine.TestListener;
import io.dtron.engine.TestOptions;
import io.dtron.engine.TestResult;
import io.dtron.engine.Verdict;
import io.dtron.engine.sim.ModelSystem;
import io.dtron.engine.sim.Mutant;
import io.dtron.engine.sim.Mutants;
import io.dtron.engine.verify.QueryException;
import io.dtron.model.ModelLoader;
import io.dtron.model.Network;
import io.dtron.model.TestInterface;
import java.nio.charset.StandardCharsets;
import java.nio.file.Path;
import java.time.Duration;
import java.util.ArrayList;
import java.util.List;
import java.util.Map;
import java.util.OptionalLong;
import org.junit.jupiter.api.Test;

class MonitorTest {
    static final Path SHARED = Path.of(System.getProperty("dtron.shared", "../../shared"), "models");
    static final long UNIT = 1000;

    /** An event of a run with its time. */
    record Timed(Event event, long micros) {
    }

    /** A run of the tester in virtual time: its events in order and its result. */
    record Run(List<Timed> events, TestResult result) {
    }

    static Network server() throws Exception {
        return ModelLoader.load("server.xta", new String(MonitorTest.class.getResourceAsStream("server.xta")
                .readAllBytes(), StandardCharsets.UTF_8));
    }

    /** Runs the tester against {@code system} (the model's implementation part, or a mutant's) in virtual time. */
    static Run run(Network spec, Network system, TestInterface ti, long seed, long timeout) {
        TestOptions o = new TestOptions(seed, UNIT, timeout, DelayPolicy.RANDOM, 0, true);
        OnlineTester tester = new OnlineTester(spec, ti, new ModelSystem(system, ti, seed * 7919), o);
        List<Timed> events = new ArrayList<>();
        tester.addListener(new TestListener() {
            @Override
            public void inputApplied(Event input, long micros) {
                events.add(new Timed(input, micros));
            }

            @Override
            public void outputObserved(Event output, long micros) {
                events.add(new Timed(output, micros));
            }
        });
        TestResult r = tester.run();
        return new Run(events, r);
    }

    /** Feeds {@code events} to {@code m}; the alarms raised, in order. */
    static List<Alarm> feed(Monitor m, List<Timed> events) {
        List<Alarm> alarms = new ArrayList<>();
        for (Timed t : events) {
            Alarm a = m.observe(t.event(), t.micros());
            if (a != null) {
                alarms.add(a);
            }
        }
        return alarms;
    }

    static Timed at(double units, String channel, String variable, int value) {
        return new Timed(Event.of(channel, variable, value), Math.round(units * UNIT));
    }

    static void correctRunsRaiseNoAlarm(Network n, TestInterface ti, long timeout, int seeds) {
        long events = 0;
        for (long seed = 1; seed <= seeds; seed++) {
            Run r = run(n, n, ti, seed, timeout);
            assertEquals(Verdict.PASSED, r.result().verdict(), r.result().explanation());
            Monitor m = Monitor.of(n, ti, MonitorOptions.initial(UNIT));
            assertEquals(List.of(), feed(m, r.events()), "seed " + seed);
            assertNull(m.advanceTo(r.result().durationMicros()), "seed " + seed);
            assertEquals(r.events().size(), m.events());
            events += m.events();
        }
        assertTrue(events > seeds, "the runs had events: " + events);
    }

    @Test
    void correctRunsOfTheSamplesRaiseNoAlarm() throws Exception {
        correctRunsRaiseNoAlarm(server(), TestInterface.fromNames(server()), 200, 10);
        Network ticker = ModelLoader.load(Path.of("../models/src/main/resources/io/dtron/models/ticker.xml"));
        correctRunsRaiseNoAlarm(ticker, TestInterface.fromNames(ticker), 300, 10);
        Network lamp = ModelLoader.load(SHARED.resolve("tron/LightContr.xml"));
        correctRunsRaiseNoAlarm(lamp, TestInterface.fromFile(lamp, SHARED.resolve("tron/LightContr.trn")), 300, 10);
        Network street = ModelLoader.load(Path.of(
                "../models/src/main/resources/io/dtron/models/streetlight/streetlight.xml"));
        correctRunsRaiseNoAlarm(street, TestInterface.fromNames(street), 300, 5);
    }

    @Test
    void aMonitorStartedBetweenARequestAndItsResponseRaisesNoAlarm() throws Exception {
        Network n = server();
        TestInterface ti = TestInterface.fromNames(n);
        // the request req(n=4) at t=9 came before the monitor started
        List<Timed> seen = List.of(at(10, "resp", "n", 5), at(12, "req", "n", 3), at(13.5, "resp", "n", 4));
        Monitor unknown = Monitor.of(n, ti, MonitorOptions.anyState(UNIT));
        assertEquals(List.of(), feed(unknown, seen));
        assertNull(unknown.advanceTo(100 * UNIT));
        // from the initial state, the same events are a violation at the first: the history explains them
        Monitor initial = Monitor.of(n, ti, MonitorOptions.initial(UNIT));
        List<Alarm> alarms = feed(initial, seen);
        assertEquals(1, alarms.size());
        assertEquals(Alarm.Reason.UNEXPECTED_EVENT, alarms.get(0).reason());
        assertEquals(10 * UNIT, alarms.get(0).micros());
        // history unknown, the monitor still narrows: a second response without a request is a violation
        Monitor narrowing = Monitor.of(n, ti, MonitorOptions.anyState(UNIT));
        assertNull(narrowing.observe(Event.of("resp", "n", 5), 10 * UNIT));
        Alarm second = narrowing.observe(Event.of("resp", "n", 6), 11 * UNIT);
        assertNotNull(second);
        assertEquals(Alarm.Reason.UNEXPECTED_EVENT, second.reason());
        assertEquals(11 * UNIT, second.micros());
        assertEquals(List.of("Server.Idle", "Client.Ready"), second.states().get(0).locations());
    }

    @Test
    void aMonitorStartedAnywhereInACorrectRunRaisesNoAlarm() throws Exception {
        Network lamp = ModelLoader.load(SHARED.resolve("tron/LightContr.xml"));
        TestInterface lampTi = TestInterface.fromFile(lamp, SHARED.resolve("tron/LightContr.trn"));
        Network n = server();
        for (Object[] c : List.of(new Object[] {n, TestInterface.fromNames(n)}, new Object[] {lamp, lampTi})) {
            Network model = (Network) c[0];
            TestInterface ti = (TestInterface) c[1];
            Run r = run(model, model, ti, 3, 2000);
            assertEquals(Verdict.PASSED, r.result().verdict(), r.result().explanation());
            assertTrue(r.events().size() > 10, "events: " + r.events().size());
            for (int k = 0; k < r.events().size(); k++) {
                Monitor m = Monitor.of(model, ti, MonitorOptions.anyState(UNIT));
                List<Timed> rest = r.events().subList(k, r.events().size());
                assertEquals(List.of(), feed(m, rest), "started at event " + k);
                assertNull(m.advanceTo(r.result().durationMicros()), "started at event " + k);
            }
        }
    }

    /**
     * An event's time give or take holds for the events after it too: the states keep when in its window it came.
     * A response 3.15 units after its request, both give or take 0.1 unit, fits the model's 1 to 3 units (the
     * request late, the response early in their windows); a tick every 12.05 units, give or take 0.1, fits a period
     * of 8 to 12 units only for two ticks (the first at 12, the second at 24), and the third misses the deadline.
     */
    @Test
    void aToleranceHoldsForThePreviousEventAsForTheNewOne() throws Exception {
        Network n = server();
        Monitor server = Monitor.of(n, TestInterface.fromNames(n), MonitorOptions.initial(UNIT));
        assertNull(server.observe(Event.of("req", "n", 4), UNIT, UNIT / 10));
        Alarm none = server.observe(Event.of("resp", "n", 5), 4150 * UNIT / 1000, UNIT / 10);
        assertNull(none, () -> none.explanation());

        Network ticker = ModelLoader.load("period.xta", "chan o_tick;\nprocess T() { clock x; state S { x <= 12 };"
                + " init S; trans S -> S { guard x >= 8; sync o_tick!; assign x = 0; }; }\n"
                + "process E() { state W; init W; trans W -> W { sync o_tick?; }; }\nsystem T, E;\n");
        Monitor m = Monitor.of(ticker, TestInterface.fromNames(ticker), MonitorOptions.initial(UNIT));
        Event tick = Event.of("tick");
        long period = 12050 * UNIT / 1000;
        assertNull(m.observe(tick, period, UNIT / 10));
        assertNull(m.observe(tick, 2 * period, UNIT / 10));
        Alarm third = m.observe(tick, 3 * period, UNIT / 10);
        assertNotNull(third, "the third tick came 12.05 units after the second at the earliest");
        // the deadline 12 units after the second tick, which came at 24 (its window's start) at the earliest
        assertEquals(Alarm.Reason.DEADLINE_MISSED, third.reason(), third.explanation());
        assertEquals(36 * UNIT, third.micros(), third.explanation());
        // on time within the tolerance: no alarm over a hundred ticks
        Monitor onTime = Monitor.of(ticker, TestInterface.fromNames(ticker), MonitorOptions.initial(UNIT));
        for (int i = 1; i <= 100; i++) {
            long at = i * 12 * UNIT + (i % 2 == 0 ? 1 : -1) * UNIT / 20;
            Alarm a = onTime.observe(tick, at, UNIT / 10);
            assertNull(a, () -> a.explanation());
        }
    }

    /**
     * A model with more reachable states than a monitor may start from (the CSMA/CD protocol of ten stations): a
     * monitor that goes on after violations reports the violation, then stops following the events, saying why,
     * instead of failing; so does one that forgets the events after a gap.
     */
    @Test
    void aMonitorThatCannotStartAgainFromEveryStateSaysSoAndKeepsWhatItJudged() throws Exception {
        Network csma = ModelLoader.load(SHARED.resolve("benchmarks/csmacd-10.xml"));
        TestInterface ti = TestInterface.fromText(csma, "csma.trn", "input begin();\noutput end();\n");
        Monitor m = Monitor.of(csma, ti, MonitorOptions.initial(UNIT).keepGoing(true));
        Alarm alarm = m.observe(Event.of("end"), 0);
        assertNotNull(alarm, "end before any begin");
        assertTrue(m.stopped() && m.gaveUp().orElse("").startsWith("it cannot re-synchronise after violation 1: the"
                + " model has too many reachable symbolic states"), m.gaveUp().toString());
        assertNull(m.observe(Event.of("begin"), 1000), "no longer followed");
        assertEquals(1, m.violations());
        Monitor gap = Monitor.of(csma, ti, MonitorOptions.initial(UNIT));
        gap.forgetHistory();
        assertTrue(gap.stopped() && gap.gaveUp().orElse("").startsWith("it cannot start again from every reachable"
                + " state after a gap in the events"), gap.gaveUp().toString());
        assertEquals(0, gap.violations());
    }

    @Test
    void aMissedDeadlineIsFoundWhenTimePassesIt() throws Exception {
        Network n = server();
        Monitor m = Monitor.of(n, TestInterface.fromNames(n), MonitorOptions.initial(UNIT));
        assertNull(m.observe(Event.of("req", "n", 1), 1000 * 1));
        assertNull(m.advanceTo(3_500));
        assertNull(m.advanceTo(4_000), "the response may come at t=4 itself");
        Alarm a = m.advanceTo(4_001);
        assertNotNull(a);
        assertEquals(Alarm.Reason.DEADLINE_MISSED, a.reason());
        assertEquals(4_000, a.micros(), "the alarm is at the deadline");
        assertNull(a.event());
        assertEquals(1_000, a.sinceMicros());
        assertEquals(List.of(new Alarm.Window("resp", Map.of("n", 2), 2_000, 4_000)), a.allowed());
        assertTrue(a.explanation().startsWith("no event by t=4.000, the deadline after the last event at t=1.000"),
                a.explanation());
        assertTrue(m.stopped());
        assertNull(m.observe(Event.of("resp", "n", 2), 5_000), "a stopped monitor ignores events");
        // found by the next event too, at the deadline's time
        Monitor late = Monitor.of(n, TestInterface.fromNames(n), MonitorOptions.initial(UNIT));
        late.observe(Event.of("req", "n", 1), 1_000);
        Alarm b = late.observe(Event.of("resp", "n", 2), 7_000);
        assertEquals(Alarm.Reason.DEADLINE_MISSED, b.reason());
        assertEquals(4_000, b.micros());
        assertEquals(Event.of("resp", "n", 2), b.event());
    }

    @Test
    void theDeadlinePendingAfterTheLastEventIsNamedWithoutChangingTheMonitor() throws Exception {
        Network n = server();
        Monitor m = Monitor.of(n, TestInterface.fromNames(n), MonitorOptions.initial(UNIT));
        assertEquals(OptionalLong.empty(), m.pendingDeadline(), "the idle server requires nothing");
        assertNull(m.observe(Event.of("req", "n", 1), 1_000));
        assertEquals(OptionalLong.of(4_000), m.pendingDeadline(), "the response is due 3 units after the request");
        assertEquals(OptionalLong.of(4_000), m.pendingDeadline(), "asking changes nothing");
        assertNull(m.advanceTo(3_000));
        assertEquals(OptionalLong.of(4_000), m.pendingDeadline(), "time passing before it leaves it where it is");
        assertNull(m.observe(Event.of("resp", "n", 2), 3_500));
        assertEquals(OptionalLong.empty(), m.pendingDeadline(), "answered: nothing is due");
        Monitor missed = Monitor.of(n, TestInterface.fromNames(n), MonitorOptions.initial(UNIT));
        missed.observe(Event.of("req", "n", 1), 1_000);
        assertNotNull(missed.advanceTo(5_000));
        assertEquals(OptionalLong.empty(), missed.pendingDeadline(), "a monitor stopped at a violation judges no more");
        Monitor joined = Monitor.of(n, TestInterface.fromNames(n), MonitorOptions.anyState(UNIT));
        assertEquals(OptionalLong.empty(), joined.pendingDeadline(), "not started: no time, no deadline");
    }

    @Test
    void aMissedDeadlineNamesNoInputThatWouldNotHaveMetIt() throws Exception {
        // the server of the monitor's tests, with a ping the client may send at any time (it changes nothing) and a
        // cancel that ends the request
        Network n = ModelLoader.load("pinged.xta", """
                chan i_req, o_resp, i_ping, i_cancel;
                int[0,9] i_req_n, o_resp_n;
                process Server() { clock x; int[0,9] n; state Idle, Busy { x <= 3 }; init Idle;
                    trans Idle -> Busy { sync i_req?; assign x = 0, n = i_req_n; },
                          Busy -> Idle { guard x >= 1; sync o_resp!; assign o_resp_n = (n + 1) % 10; },
                          Busy -> Busy { sync i_ping?; }, Idle -> Idle { sync i_ping?; },
                          Busy -> Idle { sync i_cancel?; }; }
                process Client() { state Ready, Waiting; init Ready;
                    trans Ready -> Waiting { select v : int[0,9]; sync i_req!; assign i_req_n = v; },
                          Waiting -> Ready { sync o_resp?; }, Ready -> Ready { sync i_ping!; },
                          Waiting -> Waiting { sync i_ping!; }, Waiting -> Ready { sync i_cancel!; }; }
                system Server, Client;
                """);
        String required = "the model required one of cancel() in [t=1.000, t=4.000], resp(n=2) in [t=2.000,"
                + " t=4.000] by then";
        // found when time passes the deadline, or at the next event (a ping, after it)
        for (boolean byTime : new boolean[] {true, false}) {
            Monitor m = Monitor.of(n, TestInterface.fromNames(n), MonitorOptions.initial(UNIT));
            assertNull(m.observe(Event.of("req", "n", 1), 1_000));
            Alarm a = byTime ? m.advanceTo(5_000) : m.observe(Event.of("ping"), 6_000);
            assertEquals(Alarm.Reason.DEADLINE_MISSED, a.reason());
            String expected = required + (byTime ? "" : "; the next event, ping(), came at t=6.000");
            assertTrue(a.explanation().endsWith(expected), a.explanation());
            assertTrue(a.allowed().stream().anyMatch(w -> w.channel().equals("ping")), "the ping was allowed, though");
        }
    }

    @Test
    void theLargestUncertaintyOverflowsNothing() throws Exception {
        Network n = server();
        Monitor m = Monitor.of(n, TestInterface.fromNames(n), MonitorOptions.initial(UNIT));
        assertNull(m.observe(Event.of("req", "n", 1), 1_000, TestOptions.MAX_DURATION_MICROS));
        assertNull(m.observe(Event.of("resp", "n", 2), 1_500, TestOptions.MAX_DURATION_MICROS),
                "a response some time in the window may be 1 to 3 units after the request");
        assertNotNull(m.observe(Event.of("resp", "n", 2), 2_000, TestOptions.MAX_DURATION_MICROS),
                "no time makes a second response allowed");
    }

    @Test
    void aShieldWithholdsAForbiddenEventAndGoesOnAsIfItHadNotHappened() throws Exception {
        Network n = server();
        Monitor m = Monitor.of(n, TestInterface.fromNames(n), MonitorOptions.initial(UNIT));
        assertNull(m.withhold(Event.of("req", "n", 1), 1_000, 0), "an allowed event is observed");
        assertTrue(m.allowsTimeTo(4_000));
        assertTrue(!m.allowsTimeTo(4_001) && !m.stopped(), "asking changes nothing");
        Alarm early = m.withhold(Event.of("resp", "n", 2), 1_500, 0);
        assertEquals(Alarm.Reason.UNEXPECTED_EVENT, early.reason());
        assertTrue(!m.stopped(), "a withheld event did not happen: the monitor goes on");
        assertEquals(1_000, m.lastMicros());
        // the response the model allows still comes in its window
        assertNull(m.withhold(Event.of("resp", "n", 2), 2_500, 0));
        assertEquals(1, m.violations());
        assertEquals(early, m.firstAlarm());
    }

    @Test
    void wrongValuesAndEarlyEventsAreNamed() throws Exception {
        Network n = server();
        Monitor m = Monitor.of(n, TestInterface.fromNames(n), MonitorOptions.initial(UNIT));
        m.observe(Event.of("req", "n", 1), 1_000);
        Alarm a = m.observe(Event.of("resp", "n", 7), 2_500);
        assertEquals(Alarm.Reason.WRONG_VALUES, a.reason());
        assertTrue(a.explanation().contains("it allowed resp with {n=2}"), a.explanation());
        assertEquals(List.of("Server.Busy", "Client.Waiting"), a.states().get(0).locations());
        assertEquals(1, a.states().get(0).variables().get("Server.n") == null
                ? a.states().get(0).variables().get("n") : a.states().get(0).variables().get("Server.n"));
        Monitor early = Monitor.of(n, TestInterface.fromNames(n), MonitorOptions.initial(UNIT));
        early.observe(Event.of("req", "n", 1), 1_000);
        Alarm b = early.observe(Event.of("resp", "n", 2), 1_500);
        assertEquals(Alarm.Reason.UNEXPECTED_EVENT, b.reason());
        assertEquals(1_500, b.micros());
        assertTrue(b.explanation().contains("resp(n=2) in [t=2.000, t=4.000]"), b.explanation());
        assertEquals(Map.of("number", 1, "reason", 1), b.busValues());
        assertEquals(List.of(1, 2, 3), java.util.Arrays.stream(Alarm.Reason.values()).map(Alarm.Reason::code).toList());
        assertTrue(b.toJson().startsWith("{\"kind\":\"alarm\",\"number\":1,\"reason\":\"unexpected_event\",\"t_us\":1500,"
                + "\"channel\":\"resp\",\"values\":{\"n\":2},"), b.toJson());
    }

    @Test
    void anEventKnownWithinAWindowIsAllowedWhenTheModelAllowsItSomewhereInIt() throws Exception {
        Network n = server();
        Monitor exact = Monitor.of(n, TestInterface.fromNames(n), MonitorOptions.initial(UNIT));
        exact.observe(Event.of("req", "n", 1), 1_000);
        assertNotNull(exact.observe(Event.of("resp", "n", 2), 1_800), "0.8 units after the request is too early");
        Monitor window = Monitor.of(n, TestInterface.fromNames(n), MonitorOptions.initial(UNIT));
        window.observe(Event.of("req", "n", 1), 1_000);
        assertNull(window.observe(Event.of("resp", "n", 2), 1_800, 300), "at 2.1 it is allowed");
        assertThrows(IllegalArgumentException.class, () -> window.observe(Event.of("req", "n", 1), 3_000, -1));
        Monitor tooEarly = Monitor.of(n, TestInterface.fromNames(n), MonitorOptions.initial(UNIT));
        tooEarly.observe(Event.of("req", "n", 1), 1_000);
        assertNotNull(tooEarly.observe(Event.of("resp", "n", 2), 1_800, 100), "not even at 1.9");
    }

    @Test
    void aModelNamingTheAlarmChannelIsRefused() throws Exception {
        Network n = ModelLoader.load("alarm.xta", "chan i_dtron_alarm; process P() { state S; init S; trans S -> S"
                + " { sync i_dtron_alarm?; }; } system P;");
        io.dtron.engine.UnsupportedModelException e = assertThrows(io.dtron.engine.UnsupportedModelException.class,
                () -> Monitor.of(n, TestInterface.fromNames(n), MonitorOptions.initial(UNIT)));
        assertTrue(e.getMessage().contains("'dtron_alarm' is reserved"), e.getMessage());
    }

    @Test
    void continuingCountsViolationsAndResynchronises() throws Exception {
        Network n = server();
        Monitor m = Monitor.of(n, TestInterface.fromNames(n), MonitorOptions.initial(UNIT).keepGoing(true));
        List<Timed> events = List.of(at(1, "req", "n", 1), at(2, "resp", "n", 9), // wrong value
                at(3, "req", "n", 2), at(4, "resp", "n", 3), // fine again
                at(5, "resp", "n", 4), // no request before it
                at(6, "req", "n", 5)); // fine: the server is idle
        List<Alarm> alarms = feed(m, events);
        assertEquals(List.of(2_000L, 5_000L), alarms.stream().map(Alarm::micros).toList());
        assertEquals(List.of(1, 2), alarms.stream().map(Alarm::number).toList());
        Alarm deadline = m.advanceTo(20_000);
        assertNotNull(deadline, "the request at t=6 is not answered by t=9");
        assertEquals(9_000, deadline.micros());
        assertEquals(3, m.violations());
        assertEquals(2_000, m.firstAlarm().micros());
        assertNull(m.advanceTo(30_000), "re-synchronised at the deadline, with every state possible");
        assertEquals(6, m.events());
    }

    @Test
    void aNamedStartNarrowsTheStatesAndABadOneIsRefused() throws Exception {
        Network n = server();
        TestInterface ti = TestInterface.fromNames(n);
        Monitor idle = Monitor.of(n, ti, MonitorOptions.from(UNIT, "Server.Idle"));
        Alarm a = idle.observe(Event.of("resp", "n", 1), 5_000);
        assertNotNull(a, "started idle, a response is a violation");
        Monitor busy = Monitor.of(n, ti, MonitorOptions.from(UNIT, "Server.Busy && Server.n == 3"));
        assertNotNull(busy.observe(Event.of("resp", "n", 5), 5_000), "started with n=3, only resp(n=4) is allowed");
        Monitor busy2 = Monitor.of(n, ti, MonitorOptions.from(UNIT, "Server.Busy && Server.n == 3"));
        assertNull(busy2.observe(Event.of("resp", "n", 4), 5_000));
        assertThrows(QueryException.class, () -> Monitor.of(n, ti, MonitorOptions.from(UNIT, "Server.Nowhere")));
        assertThrows(QueryException.class, () -> Monitor.of(n, ti, MonitorOptions.from(UNIT, "Server.n == 12")));
    }

    @Test
    void badEventsAreRefusedAndLeaveTheMonitorAsItWas() throws Exception {
        Network n = server();
        Monitor m = Monitor.of(n, TestInterface.fromNames(n), MonitorOptions.initial(UNIT));
        assertNull(m.observe(Event.of("req", "n", 1), 1_000));
        assertThrows(IllegalArgumentException.class, () -> m.observe(Event.of("nothing"), 2_000));
        assertThrows(IllegalArgumentException.class, () -> m.observe(Event.of("resp", "m", 2), 2_000));
        assertThrows(IllegalArgumentException.class, () -> m.observe(Event.of("resp", "n", 2), 500));
        assertNull(m.observe(Event.of("resp", "n", 2), 2_000));
        assertEquals(2, m.events());
    }

    @Test
    void seededFaultsAreFoundAtTheEventTheTesterFailed() throws Exception {
        Network lamp = ModelLoader.load(SHARED.resolve("tron/LightContr.xml"));
        int found = seededFaultsFound(lamp, TestInterface.fromFile(lamp, SHARED.resolve("tron/LightContr.trn")));
        found += seededFaultsFound(server(), TestInterface.fromNames(server()));
        assertTrue(found >= 5, "faults found: " + found);
    }

    /** Runs the tester against each mutant for a few seeds; the monitor finds each failure the tester finds. */
    static int seededFaultsFound(Network lamp, TestInterface ti) {
        int found = 0;
        for (Mutant mutant : Mutants.derive(lamp, ti, Duration.ofSeconds(5))) {
            if (mutant.invalid() != null || mutant.equivalent() != null) {
                continue;
            }
            for (long seed = 1; seed <= 3; seed++) {
                Run r = run(lamp, mutant.network(), ti, seed, 300);
                if (r.result().verdict() != Verdict.FAILED) {
                    continue;
                }
                Monitor m = Monitor.of(lamp, ti, MonitorOptions.initial(UNIT));
                List<Alarm> alarms = feed(m, r.events());
                Alarm a = alarms.isEmpty() ? m.advanceTo(r.result().durationMicros()) : alarms.get(0);
                String what = mutant.kind().label() + " " + mutant.where() + " seed " + seed + ": "
                        + r.result().explanation();
                assertNotNull(a, what);
                if (a.reason() == Alarm.Reason.DEADLINE_MISSED) {
                    assertTrue(a.micros() <= r.result().durationMicros(), what + " / " + a.explanation());
                    if (a.event() != null) {
                        assertEquals(r.events().get(r.events().size() - 1).event(), a.event(), what);
                    }
                } else {
                    Timed last = r.events().get(r.events().size() - 1);
                    assertEquals(last.event(), a.event(), what + " / " + a.explanation());
                    assertEquals(last.micros(), a.micros(), what);
                }
                found++;
                break;
            }
        }
        return found;
    }

    @Test
    void rememberedTransitionsGiveTheSameAlarmsAsComputedOnes() throws Exception {
        Network lamp = ModelLoader.load(SHARED.resolve("tron/LightContr.xml"));
        sameAlarmsRememberedOrNot(lamp, TestInterface.fromFile(lamp, SHARED.resolve("tron/LightContr.trn")));
        sameAlarmsRememberedOrNot(server(), TestInterface.fromNames(server()));
        // a periodic log with a fault every few periods (a late response, a wrong value, a response without a
        // request): its sets and delays repeat, so most steps come from memory
        List<Timed> periodic = new ArrayList<>();
        for (int i = 0; i < 60; i++) {
            long t = 10L * i;
            periodic.add(at(t + 1, "req", "n", i % 3));
            periodic.add(at(t + (i % 7 == 3 ? 5 : 3), "resp", "n", i % 3 + (i % 11 == 5 ? 2 : 1)));
            if (i % 13 == 8) {
                periodic.add(at(t + 4, "resp", "n", 0));
            }
        }
        Network n = server();
        Monitor remembering = Monitor.of(n, TestInterface.fromNames(n), MonitorOptions.initial(UNIT).keepGoing(true),
                true);
        Monitor computing = Monitor.of(n, TestInterface.fromNames(n), MonitorOptions.initial(UNIT).keepGoing(true),
                false);
        List<Alarm> alarms = feed(remembering, periodic);
        assertEquals(feed(computing, periodic), alarms);
        assertTrue(alarms.size() >= 15, "alarms: " + alarms.size());
        assertTrue(remembering.recalled() > periodic.size() / 2, "recalled: " + remembering.recalled());
    }

    /**
     * Replays the runs of the tester against each mutant (seeded faults) and against the model itself (longer), as
     * recorded and with their times rounded to whole units (a log in whole units repeats its delays, so the monitor
     * meets transitions it remembers; the rounding may also make violations), through a monitor that goes on after
     * violations, once remembering transitions and once computing every step: the same alarms, in the same order,
     * with the same states.
     */
    static void sameAlarmsRememberedOrNot(Network model, TestInterface ti) {
        int failed = 0;
        List<Network> systems = new ArrayList<>();
        for (Mutant mutant : Mutants.derive(model, ti, Duration.ofSeconds(5))) {
            if (mutant.invalid() == null && mutant.equivalent() == null) {
                systems.add(mutant.network());
            }
        }
        systems.add(model);
        for (Network system : systems) {
            for (long seed = 1; seed <= 2; seed++) {
                Run r = run(model, system, ti, seed, system == model ? 3000 : 300);
                failed += r.result().verdict() == Verdict.FAILED ? 1 : 0;
                List<Timed> rounded = new ArrayList<>();
                for (Timed t : r.events()) {
                    rounded.add(new Timed(t.event(), Math.round((double) t.micros() / UNIT) * UNIT));
                }
                for (List<Timed> events : List.of(r.events(), rounded)) {
                    String what = "system " + systems.indexOf(system) + " seed " + seed + " " + r.result().verdict();
                    Monitor remembering = Monitor.of(model, ti, MonitorOptions.initial(UNIT).keepGoing(true), true);
                    Monitor computing = Monitor.of(model, ti, MonitorOptions.initial(UNIT).keepGoing(true), false);
                    List<Alarm> expected = feed(computing, events);
                    expected.add(computing.advanceTo(r.result().durationMicros() + 1000 * UNIT));
                    List<Alarm> alarms = feed(remembering, events);
                    alarms.add(remembering.advanceTo(r.result().durationMicros() + 1000 * UNIT));
                    assertEquals(expected, alarms, what);
                    assertEquals(0, computing.recalled(), what);
                }
            }
        }
        assertTrue(failed > 0, "some runs found a fault");
    }
}
