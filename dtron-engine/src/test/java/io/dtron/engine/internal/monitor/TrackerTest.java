package io.dtron.engine.internal.monitor;

import static org.junit.jupiter.api.Assertions.assertEquals;
import static org.junit.jupiter.api.Assertions.assertTrue;

import io.dtron.engine.internal.sem.Semantics;
import io.dtron.engine.internal.sem.SymState;
import io.dtron.engine.internal.zone.Bound;
import io.dtron.engine.internal.zone.Dbm;
import io.dtron.model.ModelLoader;
import io.dtron.model.Network;
import io.dtron.model.TestInterface;
import java.nio.file.Path;
import java.util.ArrayList;
import java.util.Arrays;
import java.util.List;
import java.util.Random;
import org.junit.jupiter.api.Test;

/**
 * The tracker's sets of states are those the plain comparison of every pair of states gives, and its step keeps the
 * states the plain step (every state at the event's time, each move on the channel, the successors with the values)
 * keeps, in the same order.
 */
class TrackerTest {
    private static final Path SHARED = Path.of(System.getProperty("dtron.shared", "../../shared"), "models");

    /**
     * A set made of random states (a few discrete parts of LightContr, zones of small constants, so that many are
     * equal or within one another; short lists scanned and long ones grouped) holds exactly the states that the
     * plain way keeps: a state is added unless one kept of its discrete part covers it, and it drops those it
     * covers; in the order they were added.
     */
    @Test
    void aSetKeepsTheStatesThePlainComparisonKeeps() throws Exception {
        Network lamp = ModelLoader.load(SHARED.resolve("tron/LightContr.xml"));
        Semantics semantics = new Semantics(lamp, 1000);
        Tracker tracker = new Tracker(semantics, new boolean[lamp.channelCount()]);
        List<SymState> discrete = new ArrayList<>();
        for (SymState s : tracker.reachable(s -> true).states()) {
            if (discrete.stream().noneMatch(s::sameDiscrete)) {
                discrete.add(s);
            }
        }
        assertTrue(discrete.size() >= 3, "discrete parts: " + discrete.size());
        Random r = new Random(26);
        int dim = semantics.dimension();
        int dropped = 0;
        for (int c = 0; c < 2000; c++) {
            int parts = 1 + r.nextInt(3);
            List<SymState> states = new ArrayList<>();
            for (int k = 1 + r.nextInt(c % 5 == 0 ? 40 : 8); k > 0; k--) {
                SymState d = discrete.get(r.nextInt(parts));
                states.add(SymState.of(d.locations(), d.vars(), zone(r, dim)));
            }
            List<SymState> expected = plain(states);
            List<SymState> kept = tracker.node(states).states();
            assertEquals(expected.size(), kept.size(), "case " + c);
            for (int i = 0; i < kept.size(); i++) {
                assertTrue(expected.get(i).sameDiscrete(kept.get(i)), "case " + c);
                assertEquals(expected.get(i).zone(), kept.get(i).zone(), "case " + c);
            }
            dropped += states.size() - kept.size();
        }
        assertTrue(dropped > 1000, "states covered: " + dropped);
    }

    /** The step on random walks of LightContr (with its interface file). */
    @Test
    void aStepKeepsTheStatesThePlainStepKeepsOnLightContr() throws Exception {
        Network lamp = ModelLoader.load(SHARED.resolve("tron/LightContr.xml"));
        walk(lamp, TestInterface.fromFile(lamp, SHARED.resolve("tron/LightContr.trn")), 26);
    }

    /** The step on random walks of the street lights, whose outputs carry values most states do not give. */
    @Test
    void aStepKeepsTheStatesThePlainStepKeepsOnTheStreetLights() throws Exception {
        Network street = ModelLoader.load(Path.of("../models/src/main/resources/io/dtron/models/streetlight/"
                + "streetlight.xml"));
        walk(street, TestInterface.fromNames(street), 27);
    }

    /**
     * Random walks of events the model allows at random times (and some with a value changed, or in a window of
     * times; where no event is allowed, time passes): each step equals the plain one, computed from {@link
     * Tracker#afterWindow}'s states, which no channel filters.
     */
    private static void walk(Network n, TestInterface ti, long seed) {
        Semantics semantics = new Semantics(n, 1000);
        List<TestInterface.ObservableChannel> channels = new ArrayList<>(ti.inputs());
        channels.addAll(ti.outputs());
        boolean[] observed = new boolean[n.channelCount()];
        int[][] slots = new int[channels.size()][];
        for (int c = 0; c < channels.size(); c++) {
            observed[channels.get(c).channel()] = true;
            slots[c] = channels.get(c).variables().stream().mapToInt(v -> v.variable().offset()).toArray();
        }
        Tracker tracker = new Tracker(semantics, observed, false);
        Tracker.Node initial = tracker.node(List.of(semantics.initial()));
        Tracker.Node at = initial;
        Random r = new Random(seed);
        int allowed = 0;
        int refused = 0;
        int restarts = 0;
        for (int step = 0; step < 3000; step++) {
            // a time up to the set's deadline (or 300 units), often short
            int latest = tracker.latest(tracker.reach(at, 300_000));
            int horizon = latest == Bound.INFINITY ? 300_000 : Math.min(300_000, Bound.value(latest)) + 1;
            long from = r.nextInt(4) == 0 ? 0 : r.nextInt(r.nextBoolean() ? Math.min(horizon, 20_000) : horizon);
            long to = r.nextInt(5) == 0 ? from + r.nextInt(3_000) : from;
            List<SymState> atTime = tracker.afterWindow(at, from, to, false).states();
            List<int[]> events = new ArrayList<>(); // channel index, then values
            for (SymState s : atTime) {
                for (int c = 0; c < channels.size(); c++) {
                    int ci = c;
                    tracker.observableMoves(s, channels.get(c).channel(), (move, next) -> {
                        int[] e = new int[1 + slots[ci].length];
                        e[0] = ci;
                        for (int k = 0; k < slots[ci].length; k++) {
                            e[1 + k] = next.var(slots[ci][k]);
                        }
                        events.add(e);
                    });
                }
            }
            if (atTime.isEmpty()) {
                restarts++; // a deadline within the window
                at = initial;
                continue;
            }
            if (events.isEmpty()) {
                at = tracker.afterWindow(at, from, to, false); // time passes without an event
                continue;
            }
            int[] e = events.get(r.nextInt(events.size())).clone();
            if (e.length > 1 && r.nextInt(4) == 0) {
                e[1 + r.nextInt(e.length - 1)] += 1 + r.nextInt(2);
            }
            int c = e[0];
            int[] values = Arrays.copyOfRange(e, 1, e.length);
            int channel = channels.get(c).channel();
            List<SymState> successors = new ArrayList<>();
            for (SymState s : atTime) {
                tracker.observableMoves(s, channel, (move, next) -> {
                    boolean match = true;
                    for (int k = 0; k < values.length; k++) {
                        match &= next.var(slots[c][k]) == values[k];
                    }
                    if (match) {
                        successors.add(next);
                    }
                });
            }
            List<SymState> expected = tracker.node(successors).states();
            List<SymState> actual = tracker.step(at, channel, slots[c], values, from, to, false).states();
            assertEquals(expected.size(), actual.size(), "step " + step);
            for (int i = 0; i < actual.size(); i++) {
                assertTrue(expected.get(i).sameDiscrete(actual.get(i)), "step " + step);
                assertEquals(expected.get(i).zone(), actual.get(i).zone(), "step " + step);
            }
            if (actual.isEmpty()) {
                refused++;
            } else {
                allowed++;
                at = tracker.step(at, channel, slots[c], values, from, to, false);
            }
        }
        assertTrue(allowed > 500 && refused > 20 && restarts < 100, "allowed " + allowed + ", refused " + refused
                + ", restarts " + restarts);
    }

    /** A zone of one to three bounds with constants 0 to 2 on the first three clocks. */
    private static Dbm zone(Random r, int dim) {
        Dbm z = Dbm.unconstrained(dim);
        for (int k = r.nextInt(4); k > 0; k--) {
            int i = r.nextInt(4);
            int j = r.nextInt(4);
            if (i != j) {
                z.constrain(i, j, Bound.of((i == 0 ? -1 : 1) * r.nextInt(3), r.nextBoolean()));
            }
        }
        return z;
    }

    /** Every state not covered by one before it nor by one after it, with the first of equal ones kept. */
    private static List<SymState> plain(List<SymState> states) {
        List<SymState> kept = new ArrayList<>();
        for (SymState s : states) {
            boolean covered = false;
            for (SymState o : kept) {
                covered |= o.sameDiscrete(s) && s.zone().isSubsetOf(o.zone());
            }
            if (!covered) {
                kept.removeIf(o -> o.sameDiscrete(s) && o.zone().isSubsetOf(s.zone()));
                kept.add(s);
            }
        }
        return kept;
    }
}
