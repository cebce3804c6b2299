package io.dtron.engine.verify;

import static org.junit.jupiter.api.Assertions.assertEquals;
import static org.junit.jupiter.api.Assertions.assertFalse;
import static org.junit.jupiter.api.Assertions.assertNotNull;
import static org.junit.jupiter.api.Assertions.assertTrue;

import io.dtron.model.ModelLoader;
import io.dtron.model.Network;
import io.dtron.model.TestInterface;
import java.util.Map;
import java.util.function.Function;
import java.util.stream.Collectors;
import org.junit.jupiter.api.Test;

/** The testability checks on small lamps of the tests' own, each with one flaw or none. */
class TestabilityTest {
    /** A user who presses at most once a unit and sees the light; a lamp that lights 2 to 5 units later. */
    private static final String LAMP = """
            clock x, y;
            chan i_press, o_light;
            process User() {
                state idle;
                init idle;
                trans idle -> idle { guard y >= 1; sync i_press!; assign y = 0; },
                      idle -> idle { sync o_light?; };
            }
            process Lamp() {
                state off, on { x <= 5 };
                init off;
                trans off -> on { sync i_press?; assign x = 0; },
                      on -> off { guard x >= 2; sync o_light!; }%s;
            }
            system User, Lamp;
            """;

    private static Map<String, TestabilityReport.Check> checks(String text) throws Exception {
        Network n = ModelLoader.load("lamp.xta", text);
        TestabilityReport r = new Verifier(n, VerifierOptions.defaults()).testability(TestInterface.fromNames(n));
        assertEquals(5, r.checks().size());
        return r.checks().stream().collect(Collectors.toMap(TestabilityReport.Check::name, Function.identity()));
    }

    @Test
    void aLampThatIgnoresPressesWhileOnIsNotInputEnabled() throws Exception {
        Map<String, TestabilityReport.Check> c = checks(LAMP.formatted(""));
        TestabilityReport.Check inputs = c.get("input enabledness");
        assertFalse(inputs.passed());
        TestabilityReport.Problem p = inputs.problems().get(0);
        assertTrue(p.message().startsWith("the implementation does not accept the input press in Lamp.on"),
                p.message());
        assertNotNull(p.trace());
        assertEquals("Lamp.on", p.trace().states().get(p.trace().states().size() - 1).locations().get(1));
        assertTrue(c.get("output observability").passed());
        assertTrue(c.get("time-lock freedom").passed(), "at x = 5 the light goes on");
        assertTrue(c.get("Zeno freedom").passed(), "each press takes a unit; the lamp resets x and waits x >= 2");
        assertTrue(c.get("connectedness").passed());
    }

    @Test
    void aLampThatAcceptsEveryPressPassesEveryCheck() throws Exception {
        Map<String, TestabilityReport.Check> c = checks(LAMP.formatted(",\n on -> on { sync i_press?; }"));
        for (TestabilityReport.Check check : c.values()) {
            assertTrue(check.passed(), check.name() + ": " + check.problems());
        }
    }

    @Test
    void aLampThatCannotLightWhenItMustIsTimeLocked() throws Exception {
        // the light needs x >= 6 but on allows x <= 5 only: when the user cannot press again before x = 5 (y < 1
        // and x - y > 4), time stops at x = 5 and nothing can happen
        String locked = LAMP.formatted(",\n on -> on { sync i_press?; }").replace("guard x >= 2", "guard x >= 6");
        TestabilityReport.Check c = checks(locked).get("time-lock freedom");
        assertFalse(c.passed());
        String m = c.problems().get(0).message();
        assertTrue(m.startsWith("time cannot pass and nothing can happen in User.idle, Lamp.on when "), m);
        assertTrue(m.contains("x<=5") && m.contains("y<1"), m);
    }

    @Test
    void aLampThatFlickersWithoutTimePassingMayBeZeno() throws Exception {
        String flicker = LAMP.formatted(",\n on -> on { sync i_press?; },\n on -> on { }");
        TestabilityReport.Check c = checks(flicker).get("Zeno freedom");
        assertFalse(c.passed());
        assertEquals("the cycle on -> on of Lamp may take no time: no clock is both reset and bounded from below on it",
                c.problems().get(0).message());
    }

    @Test
    void aLocationTheEnvironmentNeverLeadsToBreaksConnectedness() throws Exception {
        String unreachable = LAMP.formatted(",\n on -> on { sync i_press?; }").replace("state off, on { x <= 5 };",
                "state off, on { x <= 5 }, broken;");
        TestabilityReport.Check c = checks(unreachable).get("connectedness");
        assertFalse(c.passed());
        assertEquals("the environment never leads the implementation to Lamp.broken", c.problems().get(0).message());
    }

    @Test
    void anOutputTheImplementationNeverSendsIsNotObservable() throws Exception {
        String silent = LAMP.formatted(",\n on -> on { sync i_press?; }").replace("chan i_press, o_light;",
                "chan i_press, o_light, o_beep;");
        TestabilityReport.Check c = checks(silent).get("output observability");
        assertFalse(c.passed());
        assertTrue(c.problems().get(0).message().startsWith("the implementation never sends the output beep"),
                c.problems().get(0).message());
    }
}
