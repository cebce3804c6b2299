package io.dtron.engine.internal.monitor;

import static org.junit.jupiter.api.Assertions.assertEquals;
import static org.junit.jupiter.api.Assertions.assertTrue;

import io.dtron.engine.internal.sem.Semantics;
import io.dtron.engine.internal.sem.SymState;
import io.dtron.engine.zone.Bound;
import io.dtron.engine.zone.Dbm;
import io.dtron.model.ModelLoader;
import io.dtron.model.Network;
import java.nio.file.Path;
import java.util.ArrayList;
import java.util.List;
import java.util.Random;
import org.junit.jupiter.api.Test;

/** The tracker's sets of states are those the plain comparison of every pair of states gives. */
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
