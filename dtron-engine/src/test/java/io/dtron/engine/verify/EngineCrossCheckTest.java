package io.dtron.engine.verify;

import static org.junit.jupiter.api.Assertions.assertEquals;
import static org.junit.jupiter.api.Assertions.assertNotNull;
import static org.junit.jupiter.api.Assertions.assertTrue;

import io.dtron.engine.internal.sem.Semantics;
import io.dtron.engine.internal.sem.SymState;
import io.dtron.engine.verify.VerificationResult.Outcome;
import io.dtron.engine.internal.zone.Bound;
import io.dtron.engine.internal.zone.Dbm;
import io.dtron.model.ClockVariable;
import io.dtron.model.Network;
import io.dtron.model.Process;
import io.dtron.model.Type;
import io.dtron.model.Variable;
import java.math.BigDecimal;
import java.util.ArrayList;
import java.util.HashMap;
import java.util.LinkedHashSet;
import java.util.List;
import java.util.Map;
import java.util.Random;
import java.util.Set;
import org.junit.jupiter.params.ParameterizedTest;
import org.junit.jupiter.params.provider.ValueSource;

/**
 * The checker against the online engine's own semantics: random runs of the engine on Uppaal's demo models only
 * reach states the checker finds reachable, and the checker's trace to each of them replays in the engine at its
 * concrete times, clock values included.
 */
class EngineCrossCheckTest {
    private static final int RUNS = 20;
    private static final int STEPS = 25;
    private static final int TARGETS = 5;

    @ParameterizedTest
    @ValueSource(strings = {"train-gate.xml", "bridge.xml", "2doors.xml", "fischer.xml"})
    void randomRunsReachOnlyWhatTheCheckerFindsAndItsTracesReplay(String file) throws Exception {
        Network n = UppaalExamplesTest.example(file);
        Semantics sem = new Semantics(n, 1);
        Random random = new Random(file.hashCode());
        Set<String> reached = new LinkedHashSet<>();
        for (int run = 0; run < RUNS; run++) {
            SymState s = sem.initial();
            sem.delay(s);
            int steps = 1 + random.nextInt(STEPS);
            for (int step = 0; step < steps; step++) {
                List<SymState> next = new ArrayList<>();
                sem.moves(s, (move, successor) -> {
                    if (sem.delay(successor)) {
                        next.add(successor);
                    }
                });
                if (next.isEmpty()) {
                    break;
                }
                s = next.get(random.nextInt(next.size()));
            }
            reached.add(property(n, s));
        }
        assertTrue(reached.size() > 1, "the runs went somewhere: " + reached);
        Verifier verifier = new Verifier(n, VerifierOptions.defaults());
        int checked = 0;
        for (String state : reached) {
            if (checked++ == TARGETS) {
                break;
            }
            VerificationResult r = verifier.verify(Query.parse("E<> " + state));
            assertEquals(Outcome.SATISFIED, r.outcome(), "the engine reached " + state);
            replay(n, r.trace());
        }
    }

    /** The discrete part of {@code s} as a state property: every location and every variable's value. */
    private static String property(Network n, SymState s) {
        List<String> parts = new ArrayList<>();
        for (Process p : n.processes()) {
            parts.add(p.name() + "." + p.locations().get(s.location(p.index())).name());
        }
        for (Variable v : n.variables()) {
            if (v.type() instanceof Type.Array a) {
                for (int i = 0; i < a.length(); i++) {
                    parts.add(v.name() + "[" + (a.firstIndex() + i) + "] == " + s.var(v.offset() + i));
                }
            } else {
                parts.add(v.name() + " == " + s.var(v.offset()));
            }
        }
        return String.join(" and ", parts);
    }

    /** Runs the trace's concrete steps in the engine, in ticks fine enough for its times. */
    static void replay(Network n, Trace trace) {
        assertNotNull(trace);
        assertTrue(!trace.concrete().isEmpty(), "a concrete trace: " + trace.toText());
        int scale = 0;
        for (Trace.ConcreteStep c : trace.concrete()) {
            scale = Math.max(scale, c.time().stripTrailingZeros().scale());
            for (BigDecimal v : c.clocks().values()) {
                scale = Math.max(scale, v.stripTrailingZeros().scale());
            }
        }
        int ticks = BigDecimal.TEN.pow(Math.max(0, scale)).intValueExact();
        Semantics sem = new Semantics(n, ticks);
        Map<String, Integer> clocks = new HashMap<>();
        for (ClockVariable c : n.clocks()) {
            for (int i = c.index(); i < c.index() + c.type().clocks(); i++) {
                clocks.put(c.elementName(i), i);
            }
        }
        SymState s = sem.initial();
        for (Trace.ConcreteStep step : trace.concrete()) {
            assertTrue(sem.delay(s), trace.toText());
            Dbm zone = s.zone();
            int now = step.time().multiply(BigDecimal.valueOf(ticks)).intValueExact();
            int elapsed = sem.elapsedClock();
            assertTrue(zone.constrain(elapsed, 0, Bound.le(now)) && zone.constrain(0, elapsed, Bound.le(-now)),
                    "time " + step.time() + " is possible: " + trace.toText());
            for (Map.Entry<String, BigDecimal> clock : step.clocks().entrySet()) {
                int x = clocks.get(clock.getKey());
                int value = clock.getValue().multiply(BigDecimal.valueOf(ticks)).intValueExact();
                Dbm point = zone.copy();
                assertTrue(point.constrain(x, 0, Bound.le(value)) && point.constrain(0, x, Bound.le(-value)),
                        clock.getKey() + " = " + clock.getValue() + " at " + step.time() + ": " + trace.toText());
            }
            if (step.transition() == null) {
                continue;
            }
            SymState[] next = new SymState[1];
            sem.moves(s, (move, successor) -> {
                List<String> edges = move.steps().stream().map(sem::describe).toList();
                String channel = move.channel() < 0 ? null : n.channelName(move.channel());
                if (next[0] == null && edges.equals(step.transition().edges())
                        && java.util.Objects.equals(channel, step.transition().channel())) {
                    next[0] = successor;
                }
            });
            assertNotNull(next[0], "the engine takes " + step.transition() + " at " + step.time() + ": "
                    + trace.toText());
            s = next[0];
        }
        List<String> locations = new ArrayList<>();
        for (Process p : n.processes()) {
            locations.add(p.name() + "." + p.locations().get(s.location(p.index())).name());
        }
        assertEquals(trace.states().get(trace.states().size() - 1).locations(), locations);
    }
}
