package io.dtron.engine.verify;

import static org.junit.jupiter.api.Assertions.assertEquals;
import static org.junit.jupiter.api.Assertions.assertFalse;
import static org.junit.jupiter.api.Assertions.assertTrue;

import io.dtron.model.ModelLoader;
import io.dtron.model.Network;
import java.util.List;
import org.junit.jupiter.api.Test;

/** The shortest time to set every trap, on small models whose answer is worked out by hand. */
class FastestCoverTest {
    /**
     * From Home, trap A is set on arriving after 3 units on a branch of its own (and the way back takes 3 more), trap B
     * after 5 (and 5 back). A first: 3, 3 back, 5 to B = 11; B first: 5, 5 back, 3 = 13. A third branch sets both at
     * once, but only 20 units after the start. The shortest is 11.
     */
    private static final String BRANCHES = """
            bool t_a, t_b;
            process P() {
                clock x, y;
                state Home, ToA { x <= 3 }, AtA { x <= 3 }, ToB { x <= 5 }, AtB { x <= 5 }, Slow;
                init Home;
                trans Home -> ToA { assign x = 0; },
                      ToA -> AtA { guard x >= 3; assign t_a = true, x = 0; },
                      AtA -> Home { guard x >= 3; },
                      Home -> ToB { assign x = 0; },
                      ToB -> AtB { guard x >= 5; assign t_b = true, x = 0; },
                      AtB -> Home { guard x >= 5; },
                      Home -> Slow { guard y >= 20; assign t_a = true, t_b = true; };
            }
            system P;
            """;

    private static CoverTime fastest(String model, List<String> traps) throws Exception {
        Network n = ModelLoader.load("model.xta", model);
        return new Verifier(n, VerifierOptions.defaults()).fastestCover(traps, 100_000);
    }

    @Test
    void theNearerTrapFirst() throws Exception {
        CoverTime t = fastest(BRANCHES, List.of("t_a", "t_b"));
        assertEquals(CoverTime.Answer.FOUND, t.answer());
        assertEquals(11, t.units());
        assertFalse(t.strict());
    }

    @Test
    void oneTrapAlone() throws Exception {
        assertEquals(3, fastest(BRANCHES, List.of("t_a")).units());
        assertEquals(5, fastest(BRANCHES, List.of("t_b")).units());
    }

    /** A trap that the model clears again still counts: it was set on the path. */
    @Test
    void aTrapClearedAgainCounts() throws Exception {
        String model = """
                bool t_a, t_b;
                process P() {
                    clock x;
                    state S0, S1, S2;
                    init S0;
                    trans S0 -> S1 { guard x >= 2; assign t_a = true, x = 0; },
                          S1 -> S2 { guard x > 4; assign t_a = false, t_b = true; };
                }
                system P;
                """;
        CoverTime t = fastest(model, List.of("t_a", "t_b"));
        assertEquals(CoverTime.Answer.FOUND, t.answer());
        assertEquals(6, t.units(), "2, then more than 4 after");
        assertTrue(t.strict(), "x > 4: any time after 6, never at 6 itself");
    }

    @Test
    void trapsThatNoRunSetsTogether() throws Exception {
        String model = """
                bool t_a, t_b;
                process P() {
                    clock x;
                    state S, A, B;
                    init S;
                    trans S -> A { guard x >= 1; assign t_a = true; },
                          S -> B { guard x >= 1; assign t_b = true; };
                }
                system P;
                """;
        CoverTime t = fastest(model, List.of("t_a", "t_b"));
        assertEquals(CoverTime.Answer.NONE, t.answer());
        assertEquals(-1, t.units());
    }

    @Test
    void theStateLimitLeavesItUnknown() throws Exception {
        Network n = ModelLoader.load("model.xta", BRANCHES);
        CoverTime t = new Verifier(n, VerifierOptions.defaults()).fastestCover(List.of("t_a", "t_b"), 2);
        assertEquals(CoverTime.Answer.UNKNOWN, t.answer());
    }
}
