package io.dtron.engine.sim;

import static org.junit.jupiter.api.Assertions.assertEquals;
import static org.junit.jupiter.api.Assertions.assertNull;
import static org.junit.jupiter.api.Assertions.assertTrue;

import io.dtron.engine.DelayPolicy;
import io.dtron.engine.TestOptions;
import io.dtron.model.ModelLoader;
import io.dtron.model.Network;
import io.dtron.model.TestInterface;
import java.io.IOException;
import java.nio.charset.StandardCharsets;
import java.time.Duration;
import java.util.List;
import org.junit.jupiter.api.Test;

/**
 * The mutants of two small models, counted by hand, and what 10 seeds of 100 time units in virtual time find.
 * beeper.xta: Beeper beeps 2..4 units after a press ({@code Wait {x <= 4}}, guard {@code x >= 2}, {@code o_beep_n =
 * 1}), then says done at once ({@code urgent Ack}); its location Never has no way in. starter.xta: go at time 0
 * ({@code S0 {x <= 0}}).
 */
class MutantsTest {
    private static final TestOptions OPTIONS = new TestOptions(1, 1000, 100, DelayPolicy.RANDOM, 0, true);

    static Network load(String name) throws IOException, io.dtron.model.ModelException {
        return ModelLoader.load(name, new String(MutantsTest.class.getResourceAsStream(name).readAllBytes(),
                StandardCharsets.UTF_8));
    }

    private static MutationReport run(String name, int threads) throws Exception {
        Network n = load(name);
        TestInterface ti = TestInterface.fromNames(n);
        return Mutants.run(n, ti, Mutants.derive(n, ti, Duration.ofSeconds(30)), OPTIONS, 10, threads);
    }

    private static String row(MutationReport.Outcome o) {
        return o.mutant().number() + " " + o.mutant().kind().label() + " | " + o.mutant().change() + " | "
                + o.mutant().where() + " | " + o.status();
    }

    @Test
    void theBeepersSixteenMutantsAsCountedByHand() throws Exception {
        MutationReport r = run("beeper.xta", 2);
        assertEquals(List.of(
                // a narrower window for the beep conforms: no test can kill it
                "1 invariant bound | Beeper.Wait: x <= 4 -> x <= 3 | beeper.xta:8 | SURVIVED",
                // a beep in (4, 5] misses the deadline
                "2 invariant bound | Beeper.Wait: x <= 4 -> x <= 5 | beeper.xta:8 | KILLED",
                // done after a delay, or never: the model wants it at once
                "3 urgency removed | Beeper.Ack urgent -> ordinary | beeper.xta:8 | KILLED",
                // a beep in [1, 2) is too early
                "4 guard bound | Beeper: Wait -> Ack: x >= 2 -> x >= 1 | beeper.xta:12 | KILLED",
                "5 guard bound | Beeper: Wait -> Ack: x >= 2 -> x >= 3 | beeper.xta:12 | SURVIVED",
                // no beep by 4: the deadline passes
                "6 output dropped | Beeper: Wait -> Ack o_beep! never enabled | beeper.xta:12 | KILLED",
                "7 output early | Beeper: Wait -> Ack o_beep!: its clock bounds 1 earlier | beeper.xta:12 | KILLED",
                "8 output late | Beeper: Wait -> Ack o_beep!: its clock bounds 1 later | beeper.xta:12 | KILLED",
                // beep(n=2) where the model says n=1
                "9 output value | Beeper: Wait -> Ack o_beep!: o_beep_n = 1 -> o_beep_n one off | beeper.xta:12 | KILLED",
                "10 output dropped | Beeper: Ack -> Idle o_done! never enabled | beeper.xta:13 | KILLED",
                // Never is unreachable (the checker proves it): all six changes of its edge are equivalent
                "11 guard bound | Beeper: Never -> Idle: x >= 1 -> x >= 0 | beeper.xta:14 | EQUIVALENT",
                "12 guard bound | Beeper: Never -> Idle: x >= 1 -> x >= 2 | beeper.xta:14 | EQUIVALENT",
                "13 output dropped | Beeper: Never -> Idle o_beep! never enabled | beeper.xta:14 | EQUIVALENT",
                "14 output early | Beeper: Never -> Idle o_beep!: its clock bounds 1 earlier | beeper.xta:14 | EQUIVALENT",
                "15 output late | Beeper: Never -> Idle o_beep!: its clock bounds 1 later | beeper.xta:14 | EQUIVALENT",
                "16 output value | Beeper: Never -> Idle o_beep!: o_beep_n = 2 -> o_beep_n one off | beeper.xta:14"
                        + " | EQUIVALENT"), r.outcomes().stream().map(MutantsTest::row).toList());
        assertEquals(8, r.count(MutationReport.Status.KILLED));
        assertEquals(10, r.total(), "equivalent mutants are not counted");
        assertEquals(0.8, r.score(), 1e-9);
        assertEquals(10, r.modelRuns(), "the model as its own system passes with every seed");
        assertNull(r.modelProblem());
        assertTrue(r.outcomes().get(8).explanation().contains("beep(n=2)"), r.outcomes().get(8).explanation());
        assertEquals("Beeper.Never is unreachable (E<> Beeper.Never does not hold)",
                r.outcomes().get(10).explanation());
    }

    @Test
    void mutantsThatCannotStartAreInvalidNeverKilled() throws Exception {
        MutationReport r = run("starter.xta", 2);
        assertEquals(List.of(
                "1 invariant bound | Starter.S0: x <= 0 -> x <= -1 | starter.xta:6 | INVALID",
                "2 invariant bound | Starter.S0: x <= 0 -> x <= 1 | starter.xta:6 | KILLED",
                "3 output dropped | Starter: S0 -> S1 o_go! never enabled | starter.xta:8 | KILLED",
                "4 output early | Starter: S0 -> S1 o_go!: its clock bounds 1 earlier | starter.xta:8 | INVALID",
                "5 output late | Starter: S0 -> S1 o_go!: its clock bounds 1 later | starter.xta:8 | KILLED"),
                r.outcomes().stream().map(MutantsTest::row).toList());
        assertEquals("the initial state violates a location invariant", r.outcomes().get(0).explanation());
        assertEquals(3, r.total());
        assertEquals(1.0, r.score(), 1e-9);
    }

    @Test
    void theLightControllersMutantsByKind() throws Exception {
        java.nio.file.Path tron = ModelSystemTest.SHARED.resolve("tron");
        Network n = ModelLoader.load(tron.resolve("LightContr.xml"));
        TestInterface ti = TestInterface.fromFile(n, tron.resolve("LightContr.trn"));
        List<Mutant> mutants = Mutants.derive(n, ti, Duration.ofSeconds(30));
        java.util.Map<Mutant.Kind, Long> kinds = new java.util.EnumMap<>(Mutant.Kind.class);
        mutants.forEach(m -> kinds.merge(m.kind(), 1L, Long::sum));
        // 9 clock bounds of invariants and 12 atoms of guards (6 on clocks, 6 comparing data with a constant), each
        // moved down and up;
        // five committed locations; the one output edge (levelAdapter's level!) dropped, early and late
        assertEquals(java.util.Map.of(Mutant.Kind.INVARIANT_BOUND, 18L, Mutant.Kind.GUARD_BOUND, 24L,
                Mutant.Kind.URGENCY_REMOVED, 5L, Mutant.Kind.OUTPUT_DROPPED, 1L, Mutant.Kind.OUTPUT_EARLY, 1L,
                Mutant.Kind.OUTPUT_LATE, 1L), kinds);
        // the checker proves switch.goingOn unreachable: the one equivalent mutant
        assertEquals(List.of("switch.goingOn committed -> ordinary"), mutants.stream()
                .filter(m -> m.equivalent() != null).map(Mutant::change).toList());
        assertTrue(mutants.stream().allMatch(m -> m.invalid() == null));
        Mutant dropped = mutants.stream().filter(m -> m.kind() == Mutant.Kind.OUTPUT_DROPPED).findFirst().orElseThrow();
        MutationReport r = Mutants.run(n, ti, List.of(dropped), OPTIONS.withTimeout(2000), 3, 1);
        assertEquals(MutationReport.Status.KILLED, r.outcomes().get(0).status(), r.outcomes().get(0).explanation());
        assertEquals(3, r.modelRuns(), "the light controller as its own system passes: " + r.modelProblem());
    }

    @Test
    void aRunIsTheSameOnOneThreadAndOnSeveral() throws Exception {
        List<String> one = run("beeper.xta", 1).outcomes().stream().map(o -> row(o) + " " + o.seed() + " "
                + o.explanation()).toList();
        List<String> four = run("beeper.xta", 4).outcomes().stream().map(o -> row(o) + " " + o.seed() + " "
                + o.explanation()).toList();
        assertEquals(one, four);
    }
}
