package io.dtron.models.lamp;

import static org.junit.jupiter.api.Assertions.assertEquals;
import static org.junit.jupiter.api.Assertions.assertNotEquals;
import static org.junit.jupiter.api.Assertions.assertThrows;

import io.dtron.engine.Event;
import io.dtron.model.ModelException;
import io.dtron.model.ModelLoader;
import io.dtron.model.TestInterface;
import io.dtron.models.VirtualRun;
import java.nio.file.Path;
import java.util.ArrayList;
import java.util.List;
import java.util.function.Consumer;
import org.junit.jupiter.api.BeforeAll;
import org.junit.jupiter.api.Test;

/**
 * The smart lamp in virtual time, against traces derived by hand from TRON's {@code LightContr.xml}. All times
 * are in model time units (1 ms, from {@code LightContr.trn}). The model's windows the comments refer to:
 * graspAdapter and releaseAdapter deliver setGrasp / setRelease 0 to 5 after the input; the Interface leaves
 * {@code ignoring} for {@code touching} at x in [20, 25], sends starthold at x in [50, 55] and touch or endhold
 * less than 5 after setRelease; the Dimmer steps at x in [100, 105]; the levelAdapter copies the level at
 * setLevel and outputs it 0 to 5 later. The lamp takes 1, 20, 50, 0, 100 and 1 in those windows.
 */
class SmartLampTest {
    private static final Event GRASP = Event.of("grasp");
    private static final Event RELEASE = Event.of("release");
    private static TestInterface lightContr;

    @BeforeAll
    static void loadModel() throws ModelException {
        Path tron = Path.of(System.getProperty("dtron.shared", "../../shared"), "models", "tron");
        lightContr = TestInterface.fromFile(ModelLoader.load(tron.resolve("LightContr.xml")),
                tron.resolve("LightContr.trn"));
    }

    private static VirtualRun lamp(String variant) {
        return new VirtualRun(new SmartLamp(variant), lightContr, lightContr.timeUnitMicros());
    }

    private static Event level(int adapLevel) {
        return Event.of("level", "adapLevel", adapLevel);
    }

    /** Grasps at {@code grasp} and releases at {@code release}. */
    private static void press(VirtualRun run, long grasp, long release) {
        run.input(grasp, GRASP);
        run.input(release, RELEASE);
    }

    /** The outputs of the lamp {@code variant} in a scenario, the time then run on to 3000. */
    private static List<VirtualRun.Output> outputs(String variant, Consumer<VirtualRun> scenario) {
        VirtualRun run = lamp(variant);
        scenario.accept(run);
        run.runUntil(3000);
        return run.outputs();
    }

    /** Level outputs from {@code (time in units, level)} pairs. */
    private static List<VirtualRun.Output> expected(int... timeLevelPairs) {
        List<VirtualRun.Output> out = new ArrayList<>();
        for (int i = 0; i < timeLevelPairs.length; i += 2) {
            out.add(new VirtualRun.Output(timeLevelPairs[i] * lightContr.timeUnitMicros(),
                    level(timeLevelPairs[i + 1])));
        }
        return out;
    }

    @Test
    void aTouchSwitchesTheLampOnAtTheOldLevel() {
        // setGrasp at 1; touching from 21; setRelease at 31 (x = 30 < 50: no starthold yet) -> touched -> touch!
        // at once; Switch on == 0: L = OL = 0 -> setLevel!, copied as adapLevel 0, level! at 32. The model allows
        // this output in [30, 45) and no other before the next input.
        assertEquals(expected(32, 0), outputs("correct", run -> press(run, 0, 30)));
    }

    @Test
    void aGraspShorterThanEpsilonIsIgnored() {
        // setGrasp at 1 and setRelease at 20: x = 19 < epsilon, still in ignoring, whose release? goes back to
        // idle without output. (Had setGrasp been fast and setRelease slow, the model would also allow a touch.)
        // From 120, x = 20 reaches epsilon: touching, so a touch, reported at 122.
        assertEquals(expected(122, 0), outputs("correct", run -> {
            press(run, 0, 19);
            press(run, 100, 120);
        }));
    }

    @Test
    void holdingDimsUpEvery100Units() {
        // setGrasp at 1; starthold at x = 50 (51); Dimmer PassiveUp: L = OL = 0, committed -> setLevel! -> level(0)
        // at 52. Up: steps at x = 100: L = 1 at 151, L = 2 at 251, each reported 1 later. setRelease arrives at
        // 251 too, after that step (the model allows both orders: the step is enabled at x >= 100, endhold any
        // time from Up), so releasing -> endhold at once and nothing more.
        assertEquals(expected(52, 0, 152, 1, 252, 2), outputs("correct", run -> press(run, 0, 250)));
    }

    @Test
    void aReleaseExactlyAtDeltaComesAfterTheHoldStarted() {
        // setGrasp and the starthold timer make the hold start at 51, where setRelease also arrives: the hold
        // comes first (allowed: touching takes both starthold and release? at x = 50). A touch would report the
        // same level(0) at 52, so the second press tells them apart: after a hold the Dimmer is PassiveDn, whose
        // starthold (at 251) reports nothing and saves OL = L = 0; at 351 Dn turns at L == 0 and steps up to 1.
        // After a touch it would be PassiveUp and report level(0) at 252.
        assertEquals(expected(52, 0, 352, 1), outputs("correct", run -> {
            press(run, 0, 50);
            press(run, 200, 400);
        }));
    }

    @Test
    void touchesSaveAndRestoreTheLevelAndHoldsAlternateDirection() {
        assertEquals(expected(
                        52, 0, 152, 1, 252, 2,  // hold up from OL = 0, as above; ends PassiveDn at level 2
                        432, 0,                 // touch, on == 1: OL = 2, L = 0, on = 0 -> level(0)
                        632, 2,                 // touch, on == 0: L = OL = 2 -> level(2)
                        952, 1, 1052, 0, 1152, 1, // hold from PassiveDn: starthold at 851 reports nothing,
                                                // steps down at 951 and 1051, turns at 0 and steps up at 1151;
                                                // endhold at 1201, before the step due at 1251: PassiveDn
                        1332, 0,                // touch: OL = 1, off
                        1432, 1),               // touch: back on at 1
                outputs("correct", run -> {
                    press(run, 0, 250);
                    press(run, 400, 430);
                    press(run, 600, 630);
                    press(run, 800, 1200);
                    press(run, 1300, 1330);
                    press(run, 1400, 1430);
                }));
    }

    @Test
    void holdingTurnsAtMaxAndTheNextHoldRestartsFromTheOldLevel() {
        // Up with L == Max = 10 and x >= 100 (1151) goes to Dn without resetting x, where L > 0 and x >= 100
        // step down at once: level(9) at 1152. endhold at 1201 leaves the Dimmer PassiveUp, whose starthold
        // assigns L = OL even though the lamp is on: the next hold (starthold at 1451) jumps from 9 to OL = 0.
        assertEquals(expected(52, 0, 152, 1, 252, 2, 352, 3, 452, 4, 552, 5, 652, 6, 752, 7, 852, 8, 952, 9,
                        1052, 10, 1152, 9, 1452, 0, 1552, 1),
                outputs("correct", run -> {
                    press(run, 0, 1200);
                    press(run, 1400, 1560);
                }));
    }

    @Test
    void inputsTheModelsInterfaceCannotTakeAreIgnored() {
        // The second grasp (the lamp is grasped) and the lone release (it is not) change nothing: the release at
        // 35 is 35 after the first grasp, a touch (it would be only 15 after the second).
        assertEquals(expected(37, 0), outputs("correct", run -> {
            run.input(0, GRASP);
            run.input(20, GRASP);
            run.input(35, RELEASE);
            run.input(100, RELEASE);
        }));
    }

    @Test
    void stopSilencesTheLamp() {
        // the touch at 31 would be reported at 32
        assertEquals(List.of(), outputs("correct", run -> {
            press(run, 0, 30);
            run.runUntil(31);
            run.stop();
        }));
    }

    @Test
    void lateReportsBeyondTheModelsLatency() {
        // A touch released at 30 must be reported before 45 (release latency <= 5, touched < 5, level latency
        // <= 5); the late lamp reports it at 51.
        assertEquals(expected(32, 0), outputs("correct", run -> press(run, 0, 30)));
        assertEquals(expected(51, 0), outputs("late", run -> press(run, 0, 30)));
    }

    @Test
    void earlyStartsDimmingBeforeDelta() {
        // The first level of a hold from PassiveUp needs setGrasp (>= 0) + starthold (x >= 50): not before 50.
        Consumer<VirtualRun> hold = run -> press(run, 0, 250);
        assertEquals(expected(52, 0, 152, 1, 252, 2), outputs("correct", hold));
        assertEquals(expected(42, 0, 142, 1, 242, 2), outputs("early", hold));
    }

    @Test
    void wrongLevelReportsALevelTheModelDoesNotAllow() {
        // The first touch switches on at OL = 0: the model allows level(0) only.
        assertEquals(expected(32, 0), outputs("correct", run -> press(run, 0, 30)));
        assertEquals(expected(32, 1), outputs("wrong-level", run -> press(run, 0, 30)));
    }

    @Test
    void missingReportsNothingWhenAHoldStarts() {
        // From PassiveUp, starthold makes the Dimmer set L = OL and take setLevel! at once (the committed location
        // after starthold): level! is due within 5 of the hold's start at 51; the missing lamp stays silent
        // until the first dimming step.
        Consumer<VirtualRun> hold = run -> press(run, 0, 250);
        assertEquals(expected(52, 0, 152, 1, 252, 2), outputs("correct", hold));
        assertEquals(expected(152, 1, 252, 2), outputs("missing", hold));
    }

    @Test
    void mutantsBehaveCorrectlyWhereTheirFaultDoesNotShow() {
        Consumer<VirtualRun> touch = run -> press(run, 0, 30);
        Consumer<VirtualRun> hold = run -> press(run, 0, 250);
        assertEquals(outputs("correct", touch), outputs("early", touch));
        assertEquals(outputs("correct", touch), outputs("missing", touch));
        // late and wrong-level change every report, but only its time or its value
        List<VirtualRun.Output> correct = outputs("correct", hold);
        List<VirtualRun.Output> late = outputs("late", hold);
        List<VirtualRun.Output> wrong = outputs("wrong-level", hold);
        assertEquals(correct.size(), late.size());
        assertEquals(correct.size(), wrong.size());
        for (int i = 0; i < correct.size(); i++) {
            assertEquals(correct.get(i).event(), late.get(i).event());
            assertEquals(correct.get(i).micros() + 19_000, late.get(i).micros());
            assertEquals(correct.get(i).micros(), wrong.get(i).micros());
            assertNotEquals(correct.get(i).event(), wrong.get(i).event());
        }
    }

    @Test
    void variantsAreSelectedByName() {
        assertEquals("correct", new SmartLamp().variant());
        assertEquals(List.of("correct", "late", "early", "wrong-level", "missing"), SmartLamp.VARIANTS);
        for (String v : SmartLamp.VARIANTS) {
            assertEquals(v, new SmartLamp(v).variant());
        }
        IllegalArgumentException e = assertThrows(IllegalArgumentException.class, () -> new SmartLamp("dim"));
        assertEquals("unknown variant 'dim' of io.dtron.models.lamp.SmartLamp; known variants: correct, late, early,"
                + " wrong-level, missing", e.getMessage());
    }

    @Test
    void rejectsAnUnknownInput() {
        SmartLamp lamp = new SmartLamp();
        VirtualRun run = new VirtualRun(lamp, lightContr, lightContr.timeUnitMicros());
        IllegalArgumentException e = assertThrows(IllegalArgumentException.class,
                () -> lamp.perform(Event.of("touch")));
        assertEquals("the lamp has no input 'touch'; its inputs are grasp and release", e.getMessage());
        press(run, 0, 30);
        run.runUntil(100);
        assertEquals(expected(32, 0), run.outputs());
    }
}
