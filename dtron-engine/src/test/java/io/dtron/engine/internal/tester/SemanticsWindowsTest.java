package io.dtron.engine.internal.tester;

import static org.junit.jupiter.api.Assertions.assertEquals;
import static org.junit.jupiter.api.Assertions.assertFalse;
import static org.junit.jupiter.api.Assertions.assertTrue;

import io.dtron.engine.internal.sem.Partition;
import io.dtron.engine.internal.sem.Semantics;
import io.dtron.model.ModelLoader;
import io.dtron.model.Network;
import io.dtron.model.TestInterface;
import java.util.List;
import java.util.Map;
import java.util.TreeMap;
import java.util.TreeSet;
import java.util.stream.Collectors;
import org.junit.jupiter.api.Test;

/**
 * The symbolic semantics seen through what the tester computes: which outputs the model allows, with which
 * values, in which windows of time (in model units, 1000 ticks each), after a given history.
 */
class SemanticsWindowsTest {
    private static final int TICKS = 1000;

    /** A model, its state set after a history of (delay in units, observable channel) steps. */
    private static final class Harness {
        final Network network;
        final TestInterface iface;
        final Semantics semantics;
        final Partition partition;
        StateSet set;

        Harness(String model) throws Exception {
            network = ModelLoader.load("m.xta", model);
            iface = TestInterface.fromNames(network);
            semantics = new Semantics(network, TICKS);
            partition = Partition.of(network, iface);
            set = StateSet.initial(semantics, partition);
        }

        /** Lets {@code units} pass, then takes observable channel {@code name}; fails if impossible. */
        Harness step(double units, String name) {
            int channel = channel(name);
            StateSet at = set.after(Math.round(units * TICKS));
            List<StateSet.Successor> succ = at.successors(channel);
            assertFalse(succ.isEmpty(), name + " is not possible after " + units);
            set = at.of(succ.stream().map(StateSet.Successor::state).toList());
            return this;
        }

        int channel(String name) {
            return iface.inputs().stream().filter(c -> c.name().equals(name)).findFirst()
                    .or(() -> iface.outputs().stream().filter(c -> c.name().equals(name)).findFirst())
                    .orElseThrow().channel();
        }

        /** Output windows "name [lo,hi]" in units, merged. */
        Map<String, String> windows() {
            Plan plan = Plan.of(set, semantics, partition, iface, 1000, 100 * TICKS);
            Map<String, String> out = new TreeMap<>();
            for (TestInterface.ObservableChannel c : iface.outputs()) {
                List<Plan.Window> ws = plan.windowsOf(c.channel());
                if (!ws.isEmpty()) {
                    out.put(c.name(), ws.stream().map(w -> "[" + units(w.lo()) + "," + units(w.hi()) + "]")
                            .collect(Collectors.joining(" ")));
                }
            }
            return out;
        }

        /** The values output {@code name} may carry right after {@code units}. */
        TreeSet<Integer> values(double units, String name, String variable) {
            int channel = channel(name);
            TestInterface.AttachedVariable v = iface.output(name).orElseThrow().variables().stream()
                    .filter(a -> a.name().equals(variable)).findFirst().orElseThrow();
            TreeSet<Integer> out = new TreeSet<>();
            for (StateSet.Successor s : set.after(Math.round(units * TICKS)).successors(channel)) {
                out.add(s.state().var(v.variable().offset()));
            }
            return out;
        }

        long deadline() {
            return Plan.of(set, semantics, partition, iface, 1000, 100 * TICKS).deadline();
        }

        private static String units(long ticks) {
            return ticks % TICKS == 0 ? String.valueOf(ticks / TICKS) : String.valueOf(ticks / (double) TICKS);
        }
    }

    private static final String ENV = """
            process Env() { state E; init E; trans E -> E { sync i_go!; }, E -> E { sync o_out?; }; }
            """;

    @Test
    void anInputIsAimedInsideTheEndOfItsWindowByTheMargin() throws Exception {
        // the environment gives i_go between 10 and 20 units
        Harness h = new Harness("""
                chan i_go, o_out;
                process Iut() { state A; init A; trans A -> A { sync i_go?; }; }
                process Env() { clock e; state W { e <= 20 }, D; init W;
                    trans W -> D { guard e >= 10; sync i_go!; }, D -> D { sync o_out?; }; }
                system Iut, Env;
                """);
        Plan plan = Plan.of(h.set, h.semantics, h.partition, h.iface, 1000, 100 * TICKS);
        java.util.Random random = new java.util.Random(1);
        // lazy: the end of the window, less the margin of 2 units
        assertEquals(18 * TICKS, plan.choose(0, random, io.dtron.engine.DelayPolicy.LAZY, 0, c -> 2 * TICKS).ticks());
        assertEquals(20 * TICKS, plan.choose(0, random, io.dtron.engine.DelayPolicy.LAZY, 0, c -> 0).ticks());
        // a window narrower than twice the margin: still the margin before its end
        assertEquals(12 * TICKS, plan.choose(0, random, io.dtron.engine.DelayPolicy.LAZY, 0, c -> 8 * TICKS).ticks());
        // narrower than the margin: its start, the time with the most room, by every policy
        for (io.dtron.engine.DelayPolicy policy : io.dtron.engine.DelayPolicy.values()) {
            assertEquals(10 * TICKS, plan.choose(0, random, policy, 5, c -> 12 * TICKS).ticks(), policy.name());
        }
        for (int i = 0; i < 200; i++) {
            long t = plan.choose(0, random, io.dtron.engine.DelayPolicy.RANDOM, 0, c -> 2 * TICKS).ticks();
            assertTrue(t >= 10 * TICKS && t <= 18 * TICKS, "chosen at " + t);
        }
    }

    @Test
    void invariantsBoundTheWindowStrictOrNot() throws Exception {
        Harness h = new Harness("""
                chan i_go, o_out;
                process Iut() { clock x; state A, B { x <= 5 }, C { x < 5 }; init A;
                    trans A -> B { sync i_go?; assign x = 0; }, B -> C { guard x >= 2; sync o_out!; assign x = 0; },
                          C -> A { sync o_out!; }; }
                """ + ENV + "system Iut, Env;");
        h.step(3, "go");
        assertEquals(Map.of("out", "[2,5]"), h.windows());
        assertEquals(5 * TICKS, h.deadline());
        h.step(4, "out");
        assertEquals(Map.of("out", "[0,4.999]"), h.windows(), "x < 5 ends one tick before 5");
    }

    @Test
    void clockOffsetsAndDataOrClockGuardsAsUppaalAllows() throws Exception {
        Harness h = new Harness("""
                chan i_go, o_out, o_alt;
                bool fast;
                process Iut() { clock x, y; state A, B { x + 2 <= 6 }; init A;
                    trans A -> B { sync i_go?; assign x = 0, fast = !fast; },
                          B -> A { guard fast || (1 + x > 4 && 6 - (y - x) <= 6); sync o_out!; },
                          B -> A { guard x + 3 == y + 1 - 1 && x >= 2; sync o_alt!; }; }
                process Env2() { state E; init E; trans E -> E { sync o_alt?; }; }
                """ + ENV + "system Iut, Env2, Env;");
        h.step(3, "go");
        // y - x == 3 from now on; fast is true: o_out any time until the invariant's x + 2 <= 6;
        // o_alt needs x + 3 == y (true) and x >= 2
        assertEquals(Map.of("out", "[0,4]", "alt", "[2,4]"), h.windows());
        h.step(1, "out").step(0, "go");
        // y - x == 4 now, so o_alt is never possible; fast is false: 1 + x > 4 means x > 3, until 4
        assertEquals(Map.of("out", "[3.001,4]"), h.windows());
    }

    @Test
    void committedLocationsAllowNoDelayAndGoFirst() throws Exception {
        Harness h = new Harness("""
                chan i_go, o_out, tick;
                int[0,9] n;
                process Iut() { state A, C; commit C; init A;
                    trans A -> C { sync i_go?; }, C -> A { sync o_out!; }; }
                process Other() { clock y; state S; init S; trans S -> S { guard y >= 1; sync tick!; assign y = 0, n = (n + 1) % 10; }; }
                process Sink() { state S; init S; trans S -> S { sync tick?; }; }
                """ + ENV + "system Iut, Other, Sink, Env;");
        h.step(1.5, "go");
        assertEquals(Map.of("out", "[0,0]"), h.windows(), "the output must come at once");
        assertEquals(0, h.deadline());
    }

    @Test
    void urgentLocationsAndUrgentChannelsAllowNoDelay() throws Exception {
        Harness h = new Harness("""
                chan i_go;
                urgent chan o_out;
                bool ready;
                process Iut() { clock x; state A, U, W; urgent U; init A;
                    trans A -> U { sync i_go?; }, U -> W { assign ready = true; }, W -> A { guard ready; sync o_out!; assign ready = false; }; }
                """ + ENV + "system Iut, Env;");
        h.step(2, "go");
        assertEquals(Map.of("out", "[0,0]"), h.windows(), "urgent U, then the urgent o_out as soon as ready");
    }

    @Test
    void selectBindingsGiveEveryValue() throws Exception {
        Harness h = new Harness("""
                chan i_go, o_out;
                int o_out_v;
                process Iut() { clock x; state A, B { x <= 3 }; init A;
                    trans A -> B { sync i_go?; assign x = 0; },
                          B -> A { select i : int[0,3]; guard x >= 1; sync o_out!; assign o_out_v = i * 10; }; }
                """ + ENV + "system Iut, Env;");
        h.step(0, "go");
        assertEquals(Map.of("out", "[1,3]"), h.windows());
        assertEquals(new TreeSet<>(List.of(0, 10, 20, 30)), h.values(2, "out", "v"));
    }

    @Test
    void broadcastReachesEveryEnabledReceiverInOrder() throws Exception {
        Harness h = new Harness("""
                chan i_go, o_out;
                broadcast chan b;
                int[0,999] o_out_v;
                int[0,999] log;
                process Iut() { state A, B; init A;
                    trans A -> B { sync i_go?; }, B -> A { sync b!; assign log = 1; }; }
                process R1() { state S, T; init S; trans S -> T { sync b?; assign log = log * 10 + 2; }; }
                process R2() { state S; init S; trans S -> S { guard log < 0; sync b?; }; }
                process R3() { state S, T; init S; trans S -> T { sync b?; assign log = log * 10 + 3; }, T -> S { sync o_out!; assign o_out_v = log; }; }
                """ + ENV + "system Iut, R1, R2, R3, Env;");
        h.step(1, "go");
        // b! sets log = 1, then R1 (x10 + 2 = 12) and R3 (x10 + 3 = 123) in system order; R2's guard is false
        assertEquals(new TreeSet<>(List.of(123)), h.values(0, "out", "v"));
    }

    @Test
    void functionsInGuardsAndUpdates() throws Exception {
        Harness h = new Harness("""
                chan i_go, o_out;
                int[0,10] q[4];
                int[0,4] len;
                int[0,10] o_out_v;
                void push(int v) { q[len] = v; len++; }
                int pop() { int r = q[0]; for (i : int[0,2]) { q[i] = q[i + 1]; } len--; return r; }
                bool empty() { return len == 0; }
                process Iut() { clock x; state A { x <= 4 }; init A;
                    trans A -> A { guard len < 3; sync i_go?; assign push(len + 5); },
                          A -> A { guard !empty() && x >= 1; sync o_out!; assign o_out_v = pop(), x = 0; }; }
                """ + ENV + "system Iut, Env;");
        h.step(0, "go").step(0, "go");
        assertEquals(new TreeSet<>(List.of(5)), h.values(1, "out", "v"), "the first pushed value comes out first");
        h.step(1, "out");
        assertEquals(new TreeSet<>(List.of(6)), h.values(1.5, "out", "v"));
    }

    @Test
    void bindingSyncsCombineSenderAndReceiverGuardsAndUpdatesInOrder() throws Exception {
        Harness h = new Harness("""
                chan i_go, o_out, internal;
                int[0,99] o_out_v;
                process A() { clock x; state S, T; init S;
                    trans S -> T { guard x >= 2; sync internal!; assign o_out_v = 7; }; }
                process B() { clock y; state S, T; init S;
                    trans S -> T { guard y <= 5; sync internal?; assign o_out_v = o_out_v * 2; }, T -> S { sync o_out!; }; }
                process Iut() { state S; init S; trans S -> S { sync i_go?; }; }
                """ + ENV + "system A, B, Iut, Env;");
        // the internal sync happens somewhere in [2,5]; then o_out may follow at once or any time later
        assertEquals(Map.of("out", "[2,100]"), h.windows());
        assertEquals(new TreeSet<>(List.of(14)), h.values(3, "out", "v"), "the sender's update runs first");
        assertTrue(h.values(1, "out", "v").isEmpty(), "not before the internal sync can happen");
    }
}
