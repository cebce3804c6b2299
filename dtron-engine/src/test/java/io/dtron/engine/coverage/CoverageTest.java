package io.dtron.engine.coverage;

import static org.junit.jupiter.api.Assertions.assertEquals;
import static org.junit.jupiter.api.Assertions.assertNull;
import static org.junit.jupiter.api.Assertions.assertThrows;
import static org.junit.jupiter.api.Assertions.assertTrue;

import io.dtron.engine.Adapter;
import io.dtron.engine.AdapterContext;
import io.dtron.engine.Event;
import io.dtron.engine.OnlineTester;
import io.dtron.engine.TestListener;
import io.dtron.engine.TestOptions;
import io.dtron.engine.TestResult;
import io.dtron.engine.Verdict;
import io.dtron.model.ModelLoader;
import io.dtron.model.Network;
import io.dtron.model.TestInterface;
import java.io.IOException;
import java.io.InputStream;
import java.nio.charset.StandardCharsets;
import java.util.ArrayList;
import java.util.List;
import java.util.Map;
import org.junit.jupiter.api.Test;

/** Coverage counted by hand, edge by edge, on two small models in virtual time. */
class CoverageTest {

    static Network model(String name) throws Exception {
        return model(name, Map.of());
    }

    /** The model of resource {@code name}, with text replaced as {@code edits} says. */
    static Network model(String name, Map<String, String> edits) throws Exception {
        String text;
        try (InputStream in = CoverageTest.class.getResourceAsStream(name)) {
            if (in == null) {
                throw new IOException("no resource " + name);
            }
            text = new String(in.readAllBytes(), StandardCharsets.UTF_8);
        }
        for (Map.Entry<String, String> e : edits.entrySet()) {
            text = text.replace(e.getKey(), e.getValue());
        }
        return ModelLoader.load(name, text);
    }

    /** press.xta's lamp: on a press when off it reports on(level=5) one unit later; a press when on turns it off. */
    static final class PressLamp implements Adapter {
        private AdapterContext context;
        private boolean on;

        @Override
        public void start(AdapterContext context) {
            this.context = context;
        }

        @Override
        public void perform(Event input) {
            if (on) {
                on = false;
                return;
            }
            on = true;
            context.clock().schedule(context.timeUnitMicros(), () -> context.report(Event.of("on", "level", 5)));
        }
    }

    /** choice.xta's implementation: done half a unit after go. */
    static final class Done implements Adapter {
        private AdapterContext context;

        @Override
        public void start(AdapterContext context) {
            this.context = context;
        }

        @Override
        public void perform(Event input) {
            context.clock().schedule(context.timeUnitMicros() / 2, () -> context.report(Event.of("done")));
        }
    }

    static OnlineTester tester(Network n, Adapter sut, long seed, long timeout) throws Exception {
        return new OnlineTester(n, TestInterface.fromNames(n), sut, TestOptions.defaults(seed).withTimeout(timeout));
    }

    static Coverage.EdgeCoverage edge(Coverage c, String process, int index) {
        return c.processes().stream().filter(p -> p.name().equals(process)).findFirst().orElseThrow().edges()
                .get(index);
    }

    static Coverage.LocationCoverage location(Coverage c, String process, String name) {
        return c.processes().stream().filter(p -> p.name().equals(process)).findFirst().orElseThrow().locations()
                .stream().filter(l -> l.name().equals(name)).findFirst().orElseThrow();
    }

    @Test
    void afterOnePressTwoOfTheFiveReachableEdgesAreTaken() throws Exception {
        OnlineTester t = tester(model("press.xta"), new PressLamp(), 1, 100);
        t.until(StopCondition.parse("inputs(1)"), Goals.NONE);
        TestResult r = t.run();
        assertEquals(Verdict.PASSED, r.verdict(), r.explanation());
        assertTrue(r.explanation().startsWith("the stop condition inputs(1) was met at t="), r.explanation());
        Coverage c = r.coverage();
        // Lamp: Off -> Dimming (press?) and User's press! edge; nothing else happened
        assertEquals(Coverage.Taken.CERTAINLY, edge(c, "Lamp", 0).taken());
        assertEquals(Coverage.Taken.NO, edge(c, "Lamp", 1).taken());
        assertEquals(Coverage.Taken.NO, edge(c, "Lamp", 2).taken());
        assertEquals(Coverage.Taken.CERTAINLY, edge(c, "User", 0).taken());
        assertEquals(Coverage.Taken.NO, edge(c, "User", 1).taken());
        // Off (initial), Dimming, Idle of the four reachable locations; Broken is not reachable
        assertEquals(Coverage.Taken.CERTAINLY, location(c, "Lamp", "Dimming").taken());
        assertEquals(Coverage.Taken.NO, location(c, "Lamp", "On").taken());
        assertEquals(new Coverage.Figure(3, 4), c.locations());
        assertEquals(new Coverage.Figure(2, 5), c.edges());
        assertEquals(new Coverage.Figure(1, 2), c.edges(true));
        assertEquals(new Coverage.Figure(1, 3), c.edges(false));
        assertEquals(new Coverage.Figure(0, 2), c.trapFigure());
        assertEquals(List.of("Lamp.Broken (line 12)", "Lamp: Off -> Broken o_off! (line 17)",
                "User: Idle -> Idle o_off? (line 26)"), c.unreachable());
        assertNull(c.reachabilityNote());
        assertEquals("coverage: locations 3/4 (75.0%), edges 2/5 (40.0%) of reachable (environment 1/2 (50.0%),"
                + " implementation 1/3 (33.3%)); unreachable: Lamp.Broken (line 12), Lamp: Off -> Broken o_off!"
                + " (line 17), User: Idle -> Idle o_off? (line 26); traps 0/2 (0.0%)", c.summary());
    }

    @Test
    void afterTwoPressesEveryReachableEdgeIsTaken() throws Exception {
        OnlineTester t = tester(model("press.xta"), new PressLamp(), 1, 100);
        t.until(StopCondition.parse("inputs(2)"), Goals.NONE);
        TestResult r = t.run();
        assertEquals(Verdict.PASSED, r.verdict(), r.explanation());
        Coverage c = r.coverage();
        // press (Off -> Dimming, press!), on (Dimming -> On, on?), press (On -> Off, press!)
        for (int e = 0; e < 3; e++) {
            assertEquals(Coverage.Taken.CERTAINLY, edge(c, "Lamp", e).taken(), "Lamp edge " + e);
        }
        assertEquals(Coverage.Taken.NO, edge(c, "Lamp", 3).taken());
        assertEquals(Coverage.Taken.CERTAINLY, edge(c, "User", 0).taken());
        assertEquals(Coverage.Taken.CERTAINLY, edge(c, "User", 1).taken());
        assertEquals(Coverage.Taken.NO, edge(c, "User", 2).taken());
        assertEquals(new Coverage.Figure(4, 4), c.locations());
        assertEquals(new Coverage.Figure(5, 5), c.edges());
        // trap_on is set on User's on? edge; trap_off only on the unreachable o_off? edge
        assertEquals(List.of(new Coverage.Trap("trap_on", Coverage.Taken.CERTAINLY),
                new Coverage.Trap("trap_off", Coverage.Taken.NO)), c.traps());
        Coverage.ChannelCoverage press = c.channels().get(0);
        assertEquals("press", press.name());
        assertTrue(press.input());
        assertEquals(2, press.count());
        Coverage.ChannelCoverage on = c.channels().get(1);
        assertEquals("on", on.name());
        assertEquals(1, on.count());
        assertEquals(List.of(Map.of("level", 5)), on.values());
        assertEquals(0, c.channels().get(2).count());
    }

    @Test
    void aSilentChoiceOfTheImplementationIsOnlyPossiblyTaken() throws Exception {
        TestResult r = tester(model("choice.xta"), new Done(), 4, 10).run();
        assertEquals(Verdict.PASSED, r.verdict(), r.explanation());
        Coverage c = r.coverage();
        // after go the implementation is in B or in C; after done in A again: each of its edges possibly taken
        for (int e = 0; e < 4; e++) {
            assertEquals(Coverage.Taken.POSSIBLY, edge(c, "Impl", e).taken(), "Impl edge " + e);
        }
        assertEquals(Coverage.Taken.CERTAINLY, edge(c, "Env", 0).taken());
        assertEquals(Coverage.Taken.CERTAINLY, edge(c, "Env", 1).taken());
        assertEquals(Coverage.Taken.POSSIBLY, location(c, "Impl", "B").taken());
        assertEquals(Coverage.Taken.POSSIBLY, location(c, "Impl", "C").taken());
        assertEquals(new Coverage.Figure(2, 4), c.locations());
        assertEquals(new Coverage.Figure(2, 6), c.edges());
        assertEquals(new Coverage.Figure(0, 4), c.edges(false));
        assertEquals(4, c.edgesPossiblyTaken());
        assertTrue(c.summary().contains("implementation 0/4 (0.0%), 4 more possibly)"), c.summary());
        assertTrue(c.unreachable().isEmpty());
    }

    /** relay.xta's implementation: done two units after go. */
    static final class Relay implements Adapter {
        private AdapterContext context;

        @Override
        public void start(AdapterContext context) {
            this.context = context;
        }

        @Override
        public void perform(Event input) {
            context.clock().schedule(2 * context.timeUnitMicros(), () -> context.report(Event.of("done")));
        }
    }

    @Test
    void anInternalEdgeThatIsTheOnlyWayIsTakenForCertain() throws Exception {
        OnlineTester t = tester(model("relay.xta"), new Relay(), 1, 100);
        t.until(StopCondition.parse("inputs(2)"), Goals.NONE);
        List<String> steps = new ArrayList<>();
        t.addListener(new TestListener() {
            @Override
            public void edgesTaken(Event event, boolean input, long micros, List<String> certainly,
                                   List<String> possibly) {
                steps.add(event + " " + certainly + " " + possibly);
            }
        });
        Coverage c = t.run().coverage();
        // go: A -> B; done: B -> C (the only internal edge out of B, and into C but for D -> C), C -> A; the
        // detour C -> D -> C may have happened or not
        assertEquals("done() [Impl: B -> C, Impl: C -> A o_done!, Env: E -> E o_done?] [Impl: C -> D, Impl: D -> C]", steps.get(1));
        assertEquals(Coverage.Taken.CERTAINLY, edge(c, "Impl", 1).taken());
        assertEquals(Coverage.Taken.POSSIBLY, edge(c, "Impl", 2).taken());
        assertEquals(Coverage.Taken.POSSIBLY, edge(c, "Impl", 3).taken());
        assertEquals(new Coverage.Figure(3, 5), c.edges(false));
        assertEquals(Coverage.Taken.POSSIBLY, location(c, "Impl", "D").taken());
        assertEquals(new Coverage.Figure(4, 5), c.locations());
    }

    @Test
    void theLocationsOfAnEdgeTakenForCertainAreVisitedForCertain() throws Exception {
        OnlineTester t = tester(model("branches.xta"), new Relay(), 1, 100);
        t.until(StopCondition.parse("inputs(2)"), Goals.NONE);
        Coverage c = t.run().coverage();
        // done leaves only from B: B -> Idle is taken for certain, so B was visited for certain, though the tester
        // cannot tell by which of the two edges from C the implementation got there
        assertEquals(Coverage.Taken.CERTAINLY, edge(c, "Impl", 4).taken());
        assertEquals(Coverage.Taken.POSSIBLY, edge(c, "Impl", 2).taken());
        assertEquals(Coverage.Taken.POSSIBLY, edge(c, "Impl", 3).taken());
        assertEquals(Coverage.Taken.CERTAINLY, location(c, "Impl", "B").taken());
        for (Coverage.ProcessCoverage p : c.processes()) {
            for (Coverage.EdgeCoverage e : p.edges()) {
                for (String l : List.of(e.source(), e.target())) {
                    assertTrue(location(c, p.name(), l).taken().compareTo(e.taken()) >= 0,
                            p.name() + "." + l + " is less certain than " + e);
                }
            }
        }
        assertEquals(new Coverage.Figure(5, 5), c.locations());
    }

    @Test
    void theListenersHearTheEdgesOfEveryStep() throws Exception {
        OnlineTester t = tester(model("press.xta"), new PressLamp(), 1, 100);
        t.until(StopCondition.parse("inputs(2)"), Goals.NONE);
        List<String> steps = new ArrayList<>();
        t.addListener(new TestListener() {
            @Override
            public void edgesTaken(Event event, boolean input, long micros, List<String> certainly,
                                   List<String> possibly) {
                steps.add(event + " " + certainly + " " + possibly);
            }
        });
        t.run();
        assertEquals(List.of("press() [Lamp: Off -> Dimming i_press?, User: Idle -> Idle i_press!] []",
                "on(level=5) [Lamp: Dimming -> On o_on!, User: Idle -> Idle o_on?] []",
                "press() [Lamp: On -> Off i_press?, User: Idle -> Idle i_press!] []"), steps);
    }

    @Test
    void aCheckWithoutBudgetCountsEverythingAsCoverableAndSaysSo() throws Exception {
        OnlineTester t = tester(model("press.xta"), new PressLamp(), 1, 100).coverableBudget(java.time.Duration.ZERO);
        t.until(StopCondition.parse("inputs(2)"), Goals.NONE);
        Coverage c = t.run().coverage();
        assertEquals(new Coverage.Figure(4, 5), c.locations());
        assertEquals(new Coverage.Figure(5, 7), c.edges());
        assertTrue(c.unreachable().isEmpty());
        assertEquals("what can be covered was not checked", c.reachabilityNote());
        assertTrue(c.summary().contains("edges 5/7 (71.4%) of coverable"), c.summary());
        assertTrue(c.summary().contains("; what can be covered was not checked"), c.summary());
    }

    @Test
    void whenTheCheckRunsOutOfBudgetTheUndecidedCountAsCoverableAndTheSummarySaysSo() throws Exception {
        Network n = model("press.xta");
        io.dtron.engine.internal.verify.Coverable partial = io.dtron.engine.internal.verify.Coverable.of(n,
                java.time.Duration.ofSeconds(30), 1);
        assertEquals("the check of what can be covered stopped at its budget of 1 stored states", partial.stopped());
        int lamp = n.process("Lamp").orElseThrow().index();
        int broken = n.process("Lamp").orElseThrow().location("Broken").index();
        assertTrue(partial.location(lamp, broken), "undecided: coverable");
        assertTrue(!partial.locationReached(lamp, broken));
        io.dtron.engine.internal.verify.Coverable complete = io.dtron.engine.internal.verify.Coverable.of(n,
                java.time.Duration.ofSeconds(30), 1000);
        assertNull(complete.stopped());
        assertTrue(!complete.location(lamp, broken), "proved unreachable");
        // merged with a run whose check was complete, the proof wins over the undecided
        Coverage unchecked = tester(n, new PressLamp(), 1, 100).coverableBudget(java.time.Duration.ZERO).run()
                .coverage();
        Coverage checked = tester(n, new PressLamp(), 2, 100).run().coverage();
        assertEquals(Coverage.Reach.UNKNOWN, location(unchecked, "Lamp", "Broken").reach());
        Coverage both = Coverage.union(List.of(unchecked, checked));
        assertEquals(Coverage.Reach.UNREACHABLE, location(both, "Lamp", "Broken").reach());
        assertNull(both.reachabilityNote());
        assertEquals(checked.unreachable(), both.unreachable());
    }

    @Test
    void namedTrapsCountAndUnknownNamesAreRefused() throws Exception {
        Network n = model("press.xta", Map.of("int[0,1] broken;", "int[0,1] broken; bool seen[2];"));
        OnlineTester t = tester(n, new PressLamp(), 1, 100).traps(List.of("seen"));
        t.until(StopCondition.parse("inputs(1)"), Goals.NONE);
        // in state-vector order: seen is declared before the traps
        assertEquals(List.of("seen[0]", "seen[1]", "trap_on", "trap_off"),
                t.run().coverage().traps().stream().map(Coverage.Trap::name).toList());
        IllegalArgumentException e = assertThrows(IllegalArgumentException.class,
                () -> tester(n, new PressLamp(), 1, 100).traps(List.of("seenn")).run());
        assertEquals("no bool variable or array called seenn to count as a trap", e.getMessage());
    }

    @Test
    void runsOfOneModelMergeAndOfAnotherAreRefused() throws Exception {
        Network n = model("press.xta");
        OnlineTester one = tester(n, new PressLamp(), 1, 100);
        one.until(StopCondition.parse("inputs(1)"), Goals.NONE);
        Coverage a = one.run().coverage();
        Coverage b = tester(model("choice.xta"), new Done(), 4, 10).run().coverage();
        OnlineTester two = tester(n, new PressLamp(), 2, 100);
        two.until(StopCondition.parse("inputs(2)"), Goals.NONE);
        Coverage c = two.run().coverage();
        Coverage all = Coverage.union(List.of(a, c));
        assertEquals(List.of(1L, 2L), all.seeds());
        assertEquals(new Coverage.Figure(5, 5), all.edges());
        assertEquals(3, all.channels().get(0).count());
        assertTrue(all.summary().endsWith("; 2 runs"), all.summary());
        IllegalArgumentException e = assertThrows(IllegalArgumentException.class,
                () -> Coverage.union(List.of(a, b)));
        assertTrue(e.getMessage().startsWith("the coverage of choice.xta is of a different model than that of"
                + " press.xta"), e.getMessage());
    }
}
