package io.dtron.engine;

import static org.junit.jupiter.api.Assertions.assertEquals;
import static org.junit.jupiter.api.Assertions.assertTrue;

import io.dtron.model.ModelLoader;
import io.dtron.model.Network;
import io.dtron.model.TestInterface;
import java.util.Optional;
import org.junit.jupiter.api.Test;

/** The narrowest time window of an observable edge, which the tester compares with the bus's delays. */
class ObservableWindowTest {

    private static Optional<ObservableWindow> narrowest(String model) throws Exception {
        Network n = ModelLoader.load("model.xta", model);
        return ObservableWindow.narrowest(n, TestInterface.fromNames(n));
    }

    @Test
    void theNarrowestOfGuardAndInvariantBoundsIsFound() throws Exception {
        Optional<ObservableWindow> w = narrowest("""
                chan i_y, o_x, internal;
                const int HIGH = 12;
                process Sut() {
                    clock x;
                    state W { x <= HIGH }, D, E { x < 50 };
                    init W;
                    trans W -> D { guard x >= 10; sync o_x!; },
                          D -> E { sync i_y?; },
                          E -> W { guard 40 < x; sync o_x!; },
                          D -> W { guard x >= 1 && x <= 1; sync internal!; };
                }
                process Env() {
                    clock e;
                    state S { e <= 8 };
                    init S;
                    trans S -> S { guard e > 3; sync i_y!; },
                          S -> S { sync o_x?; },
                          S -> S { sync internal?; };
                }
                system Sut, Env;
                """);
        assertTrue(w.isPresent());
        ObservableWindow window = w.get();
        assertEquals("o_x", window.channel());
        assertEquals("Sut", window.process());
        assertEquals("x", window.clock());
        assertEquals(10, window.lower());
        assertEquals(12, window.upper());
        assertEquals(2, window.width());
        assertTrue(window.toString().startsWith("o_x in Sut (10 <= x <= 12, model.xta:"), window.toString());
    }

    @Test
    void edgesWithoutBothBoundsGiveNoWindow() throws Exception {
        Optional<ObservableWindow> w = narrowest("""
                chan o_x;
                process Sut() {
                    clock x;
                    state W { x <= 5 };
                    init W;
                    trans W -> W { sync o_x!; assign x = 0; };
                }
                process Env() {
                    state S;
                    init S;
                    trans S -> S { sync o_x?; };
                }
                system Sut, Env;
                """);
        assertEquals(Optional.empty(), w);
    }
}
