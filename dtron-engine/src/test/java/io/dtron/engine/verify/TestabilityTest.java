package io.dtron.engine.verify;

import static org.junit.jupiter.api.Assertions.assertEquals;
import static org.junit.jupiter.api.Assertions.assertFalse;
import static org.junit.jupiter.api.Assertions.assertNotNull;
import static org.junit.jupiter.api.Assertions.assertNull;
import static org.junit.jupiter.api.Assertions.assertTrue;

import io.dtron.model.ModelLoader;
import io.dtron.model.Network;
import io.dtron.model.TestInterface;
import java.io.InputStream;
import java.nio.charset.StandardCharsets;
import java.nio.file.Path;
import java.util.List;
import java.util.Map;
import java.util.function.Function;
import java.util.stream.Collectors;
import org.junit.jupiter.api.Test;

/**
 * The testability checks on small lamps of the tests' own ({@code testability/*.xta}), each with one flaw or
 * none, and on TRON's light controller from {@code ../shared/models/tron}.
 */
class TestabilityTest {
    private static final List<String> NAMES = List.of("output observability", "input enabledness", "connectedness",
            "environment coverage", "strong responsiveness", "time-lock freedom", "Zeno freedom");

    private static Map<String, TestabilityReport.Check> checks(String model) throws Exception {
        String text;
        try (InputStream in = TestabilityTest.class.getResourceAsStream("testability/" + model)) {
            text = new String(in.readAllBytes(), StandardCharsets.UTF_8);
        }
        Network n = ModelLoader.load(model, text);
        return checks(n, TestInterface.fromNames(n));
    }

    private static Map<String, TestabilityReport.Check> checks(Network n, TestInterface ti) {
        TestabilityReport r = new Verifier(n, VerifierOptions.defaults()).testability(ti);
        assertEquals(NAMES, r.checks().stream().map(TestabilityReport.Check::name).toList());
        return r.checks().stream().collect(Collectors.toMap(TestabilityReport.Check::name, Function.identity()));
    }

    /** Asserts that only {@code failed} fail, and returns the first one's problems. */
    private static List<TestabilityReport.Problem> onlyFails(Map<String, TestabilityReport.Check> c,
                                                             String... failed) {
        List<String> expected = List.of(failed);
        for (String name : NAMES) {
            assertEquals(!expected.contains(name), c.get(name).passed(), name + ": " + c.get(name).problems());
        }
        return c.get(failed[0]).problems();
    }

    private static Trace.State last(Trace t) {
        return t.states().get(t.states().size() - 1);
    }

    @Test
    void aLampThatAcceptsEveryPressPassesEveryCheck() throws Exception {
        Map<String, TestabilityReport.Check> c = checks("lamp.xta");
        for (TestabilityReport.Check check : c.values()) {
            assertTrue(check.passed(), check.name() + ": " + check.problems());
        }
    }

    @Test
    void aLampThatIgnoresPressesWhileOnIsNotInputEnabled() throws Exception {
        List<TestabilityReport.Problem> p = onlyFails(checks("lamp-deaf.xta"), "input enabledness");
        assertEquals(1, p.size(), p.toString());
        assertEquals("the implementation does not accept the input press in Lamp.on when x<=5", p.get(0).message());
        Trace t = p.get(0).trace();
        assertNotNull(t);
        assertEquals(List.of("Lamp.on", "CanonicalTester.offering"), last(t).locations());
        assertEquals("i_press", t.transitions().get(0).channel(), "the canonical tester pressed");
    }

    @Test
    void theCanonicalTesterOffersEachElementOfAChannelArray() throws Exception {
        List<TestabilityReport.Problem> p = onlyFails(checks("lamps.xta"), "input enabledness");
        assertEquals("the implementation does not accept the input press[0] in L0.on, L1.off when L0.x<=5",
                p.get(0).message());
        assertEquals("the implementation does not accept the input press[1] in L0.off, L1.on when L1.x<=5",
                p.get(1).message());
        assertEquals("i_press[1]", p.get(1).trace().transitions().get(0).channel());
    }

    @Test
    void aPressThatLeadsToAViolatedInvariantIsRefused() throws Exception {
        // a press while on goes to dim { x <= 3 } without resetting x: the guard holds, the target invariant not
        List<TestabilityReport.Problem> p = onlyFails(checks("lamp-dim.xta"), "input enabledness");
        assertEquals("the implementation does not accept the input press in Lamp.on when x>3, x<=5",
                p.get(0).message());
        assertEquals("x>3, x<=5", last(p.get(0).trace()).zone(), "the witness's last zone is the refused part");
    }

    @Test
    void everyValueOfAnInputsVariableIsOffered() throws Exception {
        // the model's user presses with level 2 only; the canonical tester offers 0 to 3, and on needs level >= 1
        List<TestabilityReport.Problem> p = onlyFails(checks("lamp-level.xta"), "input enabledness");
        assertEquals(1, p.size(), p.toString());
        assertEquals("the implementation does not accept the input press with level=0 in Lamp.off", p.get(0).message());
    }

    @Test
    void aVariableWithTooManyValuesIsSentAsItIsAndSaidSo() throws Exception {
        Network n = ModelLoader.load("lamp-level.xta", new String(TestabilityTest.class.getResourceAsStream(
                "testability/lamp-level.xta").readAllBytes(), StandardCharsets.UTF_8).replace("int[0,3] i_press_level",
                "int i_press_level"));
        TestabilityReport.Check inputs = checks(n, TestInterface.fromNames(n)).get("input enabledness");
        assertTrue(inputs.passed(), "the tester sends level 1, its initial value: " + inputs.problems());
        assertEquals("partly: input press is offered with i_press_level as it is (initially 1): its 65536 values are"
                + " too many to offer each", inputs.note());
    }

    @Test
    void aLampThatBreaksDeadlocksWithTheCanonicalTester() throws Exception {
        Map<String, TestabilityReport.Check> c = checks("lamp-stuck.xta");
        List<TestabilityReport.Problem> p = onlyFails(c, "connectedness", "input enabledness", "environment coverage");
        assertEquals("deadlock with the canonical tester in Lamp.stuck: the implementation takes no input and does"
                + " nothing, now or after any delay", p.get(0).message());
        Trace t = p.get(0).trace();
        assertEquals(List.of("Lamp.stuck", "CanonicalTester.offering"), last(t).locations());
        assertEquals(2, t.transitions().size(), "two presses: the second breaks the lamp");
        assertEquals("the model's environment never leads the implementation to Lamp.stuck",
                c.get("environment coverage").problems().get(0).message());
    }

    @Test
    void aLocationNoEdgeLeadsToBreaksConnectedness() throws Exception {
        List<TestabilityReport.Problem> p = onlyFails(checks("lamp-broken.xta"), "connectedness");
        assertEquals(1, p.size(), p.toString());
        assertEquals("Lamp.broken is unreachable, even with a tester that offers every input at any time",
                p.get(0).message());
        assertNull(p.get(0).trace());
    }

    @Test
    void aLocationOnlyTheCanonicalTesterReachesIsNotCoveredByTheEnvironment() throws Exception {
        List<TestabilityReport.Problem> p = onlyFails(checks("lamp-double.xta"), "environment coverage");
        assertEquals(List.of("the model's environment never leads the implementation to Lamp.bright"),
                p.stream().map(TestabilityReport.Problem::message).toList());
    }

    @Test
    void aLampThatMayBlinkForEverIsNotStronglyResponsive() throws Exception {
        List<TestabilityReport.Problem> p = onlyFails(checks("lamp-blink.xta"), "strong responsiveness");
        assertEquals("the implementation can move for ever without an input or an output: a cycle of internal moves"
                + " from Lamp.on", p.get(0).message());
        Trace t = p.get(0).trace();
        assertTrue(t.loopStart() >= 1, "a lasso after the first press: " + t.toText());
        assertEquals("i_press", t.transitions().get(0).channel());
        for (Trace.Transition move : t.transitions().subList(t.loopStart(), t.transitions().size())) {
            assertNull(move.channel(), "the loop is internal: " + t.toText());
            assertEquals(List.of("Lamp: on -> on"), move.edges());
        }
    }

    @Test
    void aLampThatCannotLightWhenItMustIsTimeLocked() throws Exception {
        // with the model's user the lamp time-locks; a canonical tester could always press, so it does not deadlock
        List<TestabilityReport.Problem> p = onlyFails(checks("lamp-locked.xta"), "time-lock freedom");
        String m = p.get(0).message();
        assertTrue(m.startsWith("time cannot pass and nothing can happen in User.idle, Lamp.on when "), m);
        assertTrue(m.contains("x<=5") && m.contains("y<1"), m);
    }

    @Test
    void aLampThatFlickersWithoutTimePassingMayBeZeno() throws Exception {
        Map<String, TestabilityReport.Check> c = checks("lamp-flicker.xta");
        List<TestabilityReport.Problem> p = onlyFails(c, "Zeno freedom", "strong responsiveness");
        assertEquals(List.of("a cycle of moves can run for ever with no time passing, from User.idle, Lamp.on",
                "the cycle on -> on of Lamp may take no time: no clock is both reset and bounded from below on it"),
                p.stream().map(TestabilityReport.Problem::message).toList());
        Trace t = p.get(0).trace();
        assertEquals(List.of("User.idle", "Lamp.on"), t.states().get(t.loopStart()).locations());
        assertEquals(List.of("Lamp: on -> on"), t.transitions().get(t.transitions().size() - 1).edges());
        for (Trace.ConcreteStep step : t.concrete().subList(t.loopStart() + 1, t.concrete().size())) {
            assertEquals(0, step.delay().signum(), "no time passes on the cycle: " + t.toText());
        }
        assertNull(p.get(1).trace(), "the structural finding has no trace");
    }

    @Test
    void aCycleThatOnlyItsPartnerMakesTakeTimeIsFlaggedStructurallyOnly() throws Exception {
        List<TestabilityReport.Problem> p = onlyFails(checks("lamp-waiting.xta"), "Zeno freedom");
        assertEquals(List.of("the cycle idle -> waiting -> idle of User may take no time: no clock is both reset and"
                + " bounded from below on it"), p.stream().map(TestabilityReport.Problem::message).toList());
    }

    @Test
    void anOutputTheImplementationNeverSendsIsNotObservable() throws Exception {
        Network n = ModelLoader.load("lamp.xta", new String(TestabilityTest.class.getResourceAsStream(
                "testability/lamp.xta").readAllBytes(), StandardCharsets.UTF_8).replace("chan i_press, o_light;",
                "chan i_press, o_light, o_beep;"));
        List<TestabilityReport.Problem> p = onlyFails(checks(n, TestInterface.fromNames(n)), "output observability");
        assertTrue(p.get(0).message().startsWith("the implementation never sends the output beep"), p.get(0).message());
    }

    @Test
    void aSearchStoppedByItsTimeLimitLeavesTheChecksUnknownNotFailed() throws Exception {
        Path dir = Path.of(System.getProperty("dtron.shared", "../../shared"), "models", "tron");
        Network n = ModelLoader.load(dir.resolve("LightContr.xml"));
        TestabilityReport r = new Verifier(n, VerifierOptions.defaults().withTimeLimit(java.time.Duration.ofNanos(1)))
                .testability(TestInterface.fromFile(n, dir.resolve("LightContr.trn")));
        Map<String, TestabilityReport.Check> c = r.checks().stream().collect(Collectors.toMap(
                TestabilityReport.Check::name, Function.identity()));
        for (String name : List.of("connectedness", "environment coverage", "strong responsiveness",
                "time-lock freedom")) {
            assertTrue(c.get(name).note().startsWith("unknown: "), name + ": " + c.get(name).note());
            assertTrue(c.get(name).passed(), "no location is called unreachable from a partial search: "
                    + c.get(name).problems());
        }
    }

    @Test
    void tronsLightControllerHasAdaptersThatAreBusyForALatency() throws Exception {
        Path dir = Path.of(System.getProperty("dtron.shared", "../../shared"), "models", "tron");
        Network n = ModelLoader.load(dir.resolve("LightContr.xml"));
        Map<String, TestabilityReport.Check> c = checks(n, TestInterface.fromFile(n, dir.resolve("LightContr.trn")));
        // the adapters of grasp and release take an input and pass it on within the latency, refusing another
        List<TestabilityReport.Problem> p = c.get("input enabledness").problems();
        assertFalse(p.isEmpty());
        assertTrue(p.get(0).message().startsWith("the implementation does not accept the input grasp in "),
                p.get(0).message());
        assertTrue(p.get(0).message().contains("graspAdapter._id27") && p.get(0).message().endsWith(
                " when graspAdapter.x<=5"), p.get(0).message());
        assertTrue(c.get("connectedness").passed(), c.get("connectedness").problems().toString());
        assertTrue(c.get("strong responsiveness").passed(), c.get("strong responsiveness").problems().toString());
        assertTrue(c.get("time-lock freedom").passed(), c.get("time-lock freedom").problems().toString());
    }
}
