package io.dtron.engine.internal.sem;

import static org.junit.jupiter.api.Assertions.assertEquals;
import static org.junit.jupiter.api.Assertions.assertTrue;

import io.dtron.engine.internal.zone.Bound;
import io.dtron.model.ModelLoader;
import io.dtron.model.Network;
import java.util.ArrayDeque;
import java.util.ArrayList;
import java.util.Arrays;
import java.util.Deque;
import java.util.List;
import java.util.function.IntPredicate;
import org.junit.jupiter.api.Test;

/**
 * {@link DiscreteCache} gives every state exactly the delay (up to a bound on the tester's clock), the successors
 * (all, and those on each channel) and the bounds of the tester's clock in them that {@link Semantics} gives it, in the same order, over the first
 * few hundred states of models with data, selects, binary, broadcast and urgent channels, committed locations,
 * data-dependent invariants and clock differences.
 */
class DiscreteCacheTest {
    private static final String MIXED = """
            int[0,5] count;
            int turn = 0;
            broadcast chan go;
            urgent chan hurry;
            chan msg[3];
            clock g;
            process P(const int[0,2] id) {
              clock x;
              state A { x <= 4 }, B { x <= count + 2 }, C;
              commit C;
              init A;
              trans
                A -> B { select i : int[0,2]; guard x >= 1 && i != id && x - g < 5; sync msg[i]!;
                         assign x = 0, count = (count + 1) % 6; },
                A -> A { sync msg[id]?; assign turn = id; },
                B -> C { guard x > 1 && turn == id; sync go!; },
                B -> A { guard turn != id; sync go?; assign x = 0; },
                C -> A { assign g = 0; },
                A -> A { guard count > 2; sync hurry!; assign count = 0; };
            }
            process Q() { state I, J { g <= 7 }; init I;
              trans I -> I { sync hurry?; }, I -> J { sync go?; }, J -> I { guard g >= 1; }; }
            system P, Q;
            """;

    private static final String TIMERS = """
            chan set, fire[3];
            process Env() { state E; init E; trans E -> E { sync set!; }, E -> E { sync fire[0]?; },
              E -> E { sync fire[1]?; }, E -> E { sync fire[2]?; }; }
            process T(const int[0,2] id) { clock x; state Idle, Set { x <= 10 }; init Idle;
              trans Idle -> Set { sync set?; assign x = 0; }, Set -> Idle { guard x >= 2; sync fire[id]!; },
              Set -> Set { sync set?; }; }
            system Env, T;
            """;

    @Test
    void mixedModelAllChannels() throws Exception {
        compare(MIXED, c -> true, 1000);
    }

    @Test
    void mixedModelSomeChannels() throws Exception {
        compare(MIXED, c -> c != 0, 3);
    }

    @Test
    void timersAllChannels() throws Exception {
        compare(TIMERS, c -> true, 1000);
    }

    /** Compares over the first states of {@code model}, with a cache that starts again after {@code limit} parts. */
    private static void compare(String model, IntPredicate channels, int limit) throws Exception {
        Network network = ModelLoader.load("m.xta", model);
        Semantics semantics = new Semantics(network, 1000);
        List<SymState> states = explore(semantics, 300);
        assertTrue(states.size() > 10, "explored " + states.size());
        DiscreteCache cache = new DiscreteCache(semantics, channels, limit);
        int successors = 0;
        int mayNot = 0;
        int valuesRuledOut = 0;
        for (SymState s : states) {
            List<String> expected = new ArrayList<>();
            semantics.moves(s, channels, (move, next) -> expected.add(describe(semantics, move, next)));
            List<String> actual = new ArrayList<>();
            cache.moves(s, (move, next) -> actual.add(describe(semantics, move, next)));
            assertEquals(expected, actual, "successors of " + s);
            successors += expected.size();

            for (int channel = 0; channel < semantics.network().channelCount(); channel++) {
                int only = channel;
                if (!channels.test(only)) {
                    continue;
                }
                List<String> expectedOn = new ArrayList<>();
                semantics.moves(s, c -> c == only, (move, next) -> expectedOn.add(describe(semantics, move, next)));
                List<String> actualOn = new ArrayList<>();
                cache.moves(s, only, (move, next) -> actualOn.add(describe(semantics, move, next)));
                assertEquals(expectedOn, actualOn, "successors on channel " + only + " of " + s);
                if (!cache.mayMove(s, only, new int[0], new int[0])) {
                    assertEquals(List.of(), expectedOn, "no move on channel " + only + " of " + s);
                    mayNot++;
                }
                // with values: false only when no successor has them, true whenever one has
                List<int[]> successorVars = new ArrayList<>();
                semantics.moves(s, c -> c == only, (move, next) -> successorVars.add(next.vars()));
                for (int slot = 0; slot < s.vars().length; slot++) {
                    int[] slots = {slot};
                    for (int value : new int[] {s.var(slot), s.var(slot) + 1, -7}) {
                        int[] values = {value};
                        boolean some = successorVars.stream().anyMatch(v -> v[slots[0]] == values[0]);
                        boolean may = cache.mayMove(s, only, slots, values);
                        assertTrue(may || !some, "a successor on " + only + " of " + s + " has " + value + " at "
                                + slot);
                        valuesRuledOut += may ? 0 : 1;
                    }
                }
            }
            // a subset of the channels by a predicate, as the monitor asks for its internal moves
            IntPredicate odd = c -> channels.test(c) && (c < 0 || c % 2 == 1);
            List<String> expectedOdd = new ArrayList<>();
            semantics.moves(s, odd, (move, next) -> expectedOdd.add(describe(semantics, move, next)));
            List<String> actualOdd = new ArrayList<>();
            cache.moves(s, odd, (move, next) -> actualOdd.add(describe(semantics, move, next)));
            assertEquals(expectedOdd, actualOdd, "successors on odd channels of " + s);

            SymState e1 = s.copy();
            SymState e2 = s.copy();
            e1.zone().up();
            e2.zone().up();
            semantics.extrapolate(e1);
            cache.extrapolate(e2);
            assertEquals(e1.toString(), e2.toString(), "extrapolation of " + s);

            int clock = semantics.elapsedClock();
            List<String> expectedBounds = new ArrayList<>();
            semantics.moves(s, channels, (move, next) -> expectedBounds.add(describe(semantics, move)
                    + next.zone().upperBound(clock, 0) + " " + next.zone().upperBound(0, clock)));
            List<String> actualBounds = new ArrayList<>();
            cache.clockBounds(s, clock, (move, upper, lowerNeg) -> actualBounds.add(describe(semantics, move)
                    + upper + " " + lowerNeg));
            assertEquals(expectedBounds, actualBounds, "bounds after " + s);

            SymState a = s.copy();
            SymState b = s.copy();
            int bound = Bound.le(4500);
            boolean expectedDelay = semantics.delay(a) && a.zone().constrain(clock, 0, bound);
            assertEquals(expectedDelay, cache.delay(b, clock, bound), "delay of " + s);
            assertEquals(a.toString(), b.toString(), "delay of " + s);
        }
        assertTrue(successors > 10, "successors " + successors);
        assertTrue(mayNot > 0, "states without a move on some channel");
        assertTrue(valuesRuledOut > 0 || states.stream().allMatch(s -> s.vars().length == 0),
                "values no successor has");
    }

    /** The first {@code max} states of the zone graph, breadth first, delayed and extrapolated. */
    private static List<SymState> explore(Semantics semantics, int max) {
        List<SymState> out = new ArrayList<>();
        Deque<SymState> waiting = new ArrayDeque<>();
        SymState initial = semantics.initial();
        semantics.delay(initial);
        waiting.add(initial);
        while (!waiting.isEmpty() && out.size() < max) {
            SymState s = waiting.poll();
            if (out.stream().anyMatch(o -> o.sameDiscrete(s) && o.zone().equals(s.zone()))) {
                continue;
            }
            out.add(s);
            semantics.moves(s, (move, next) -> {
                if (semantics.delay(next)) {
                    semantics.extrapolate(next);
                    waiting.add(next);
                }
            });
        }
        return out;
    }

    private static String describe(Semantics semantics, Semantics.Move move, SymState next) {
        return describe(semantics, move) + next;
    }

    private static String describe(Semantics semantics, Semantics.Move move) {
        StringBuilder sb = new StringBuilder().append(move.channel());
        for (Semantics.Step step : move.steps()) {
            sb.append(' ').append(semantics.describe(step)).append('#').append(System.identityHashCode(step.edge()))
                    .append(Arrays.toString(step.frame()));
        }
        return sb.append(" -> ").toString();
    }
}
