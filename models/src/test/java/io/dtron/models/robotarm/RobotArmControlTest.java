package io.dtron.models.robotarm;

import static org.junit.jupiter.api.Assertions.assertEquals;
import static org.junit.jupiter.api.Assertions.assertFalse;
import static org.junit.jupiter.api.Assertions.assertNull;
import static org.junit.jupiter.api.Assertions.assertTrue;

import io.dtron.engine.Adapter;
import io.dtron.engine.AdapterContext;
import io.dtron.engine.Event;
import io.dtron.engine.TestOptions;
import io.dtron.engine.control.ControlListener;
import io.dtron.engine.control.ControlPolicy;
import io.dtron.engine.control.ControlResult;
import io.dtron.engine.control.Controller;
import io.dtron.engine.control.ModelVersion;
import io.dtron.engine.control.SafeAction;
import io.dtron.engine.sim.ModelSystem;
import io.dtron.engine.sim.Mutant;
import io.dtron.engine.sim.Mutants;
import io.dtron.engine.verify.Query;
import io.dtron.model.ModelLoader;
import io.dtron.model.Network;
import io.dtron.model.TestInterface;
import java.io.InputStream;
import java.nio.charset.StandardCharsets;
import java.time.Duration;
import java.util.ArrayList;
import java.util.List;
import org.junit.jupiter.api.Test;

/**
 * The robot-arm sample under control in virtual time, the model's own plant part as the plant: control runs its
 * duration with every command in the model's order; a plant that stalls (the mutant whose arrived is dropped) raises
 * the alarm within the model's bound (5 time units after move, plus the tick in which the bound is seen to pass) and
 * the safe action is taken; a version that satisfies the sample's queries is taken at a reset point mid-run, one
 * that breaks one is refused and the run goes on with the old one.
 */
class RobotArmControlTest {
    private static final String FOLDER = "io/dtron/models/robotarm/";
    private static final long UNIT = 1000;
    /** One tick of the engine at 1000 us per unit: 1 us. */
    private static final long TICK = 1;

    private static Network load(String name) throws Exception {
        return ModelLoader.loadResource(RobotArmControlTest.class.getClassLoader(), FOLDER + name);
    }

    private static List<Query> queries() throws Exception {
        try (InputStream in = RobotArmControlTest.class.getClassLoader().getResourceAsStream(FOLDER + "robot-arm.q")) {
            return Query.parseFile(new String(in.readAllBytes(), StandardCharsets.UTF_8));
        }
    }

    /** What happened in a run, in order, with times in microseconds. */
    private static final class Log implements ControlListener {
        final List<String> events = new ArrayList<>();
        final List<Long> times = new ArrayList<>();
        final List<String> taken = new ArrayList<>();
        long alarmMicros = -1;

        @Override
        public void commandSent(Event command, long micros) {
            events.add(command.channel());
            times.add(micros);
        }

        @Override
        public void readingTaken(Event reading, long micros) {
            events.add(reading.channel());
            times.add(micros);
        }

        @Override
        public void alarm(String reason, long micros) {
            alarmMicros = micros;
        }

        @Override
        public void versionTaken(String version, long micros) {
            taken.add(version + "@" + micros);
        }

        /** When the last {@code channel} before {@code index} happened. */
        long lastBefore(String channel, int index) {
            for (int i = index - 1; i >= 0; i--) {
                if (events.get(i).equals(channel)) {
                    return times.get(i);
                }
            }
            throw new AssertionError("no " + channel + " before event " + index + ": " + events);
        }
    }

    /** The plant with the commands it was given, as they reached it. */
    private static final class RecordingPlant implements Adapter {
        final Adapter plant;
        final List<String> given = new ArrayList<>();
        AdapterContext context;

        RecordingPlant(Adapter plant) {
            this.plant = plant;
        }

        @Override
        public void start(AdapterContext context) {
            this.context = context;
            plant.start(context);
        }

        @Override
        public void perform(Event input) {
            given.add(input.channel() + "@" + context.clock().nowMicros());
            plant.perform(input);
        }

        @Override
        public void stop() {
            plant.stop();
        }
    }

    private static TestOptions options(long seed, long units) {
        return TestOptions.defaults(seed).withTimeUnit(UNIT).withTimeout(units);
    }

    @Test
    void theSampleHasItsCommandsAndReadingsAndSatisfiesItsQueries() throws Exception {
        for (String file : List.of("robot-arm.xta", "robot-arm-v2.xta", "robot-arm-slow.xta")) {
            Network n = load(file);
            assertTrue(n.warnings().isEmpty(), file + ": " + n.warnings());
            TestInterface i = TestInterface.fromNames(n);
            assertEquals(List.of("move", "grip", "release", "stop"), i.inputs().stream()
                    .map(TestInterface.ObservableChannel::name).toList(), file);
            assertEquals(List.of("arrived", "gripped"), i.outputs().stream()
                    .map(TestInterface.ObservableChannel::name).toList(), file);
        }
        Network arm = load("robot-arm.xta");
        ModelVersion.Check itself = ModelVersion.check(new ModelVersion("robot-arm.xta", arm,
                TestInterface.fromNames(arm)), TestInterface.fromNames(arm), queries());
        assertTrue(itself.accepted(), itself.refusal());
    }

    @Test
    void controlRunsItsDurationWithTheCommandsInTheModelsOrder() throws Exception {
        Network arm = load("robot-arm.xta");
        TestInterface names = TestInterface.fromNames(arm);
        for (ControlPolicy policy : List.of(ControlPolicy.EAGER, ControlPolicy.RANDOM)) {
            for (long seed = 1; seed <= 10; seed++) {
                Log log = new Log();
                ControlResult r = new Controller(arm, names, new ModelSystem(arm, names, ModelSystem.seedFor(seed)),
                        options(seed, 200)).policy(policy, List.of()).safeAction(SafeAction.channel("i_stop"))
                        .addListener(log).run();
                String what = policy + " seed " + seed + ": " + r;
                assertEquals(ControlResult.Outcome.COMPLETED, r.outcome(), what);
                assertEquals(200 * UNIT, r.durationMicros(), what);
                assertEquals(0, r.alarms(), what);
                assertNull(r.safeAction(), what);
                List<String> cycle = List.of("move", "arrived", "grip", "gripped", "release");
                assertTrue(log.events.size() >= cycle.size() * 10, "200 units hold at least 10 cycles: " + what);
                for (int i = 0; i < log.events.size(); i++) {
                    assertEquals(cycle.get(i % cycle.size()), log.events.get(i), "event " + i + ", " + what);
                    long since = i == 0 ? 0 : log.times.get(i) - log.times.get(i - 1);
                    switch (log.events.get(i)) {
                        case "arrived" -> assertTrue(since >= 2 * UNIT && since <= 5 * UNIT, "arrived " + since);
                        case "gripped" -> assertTrue(since >= UNIT && since <= 2 * UNIT, "gripped " + since);
                        case "release" -> assertTrue(since >= 3 * UNIT && since <= 4 * UNIT, "release " + since);
                        default -> assertTrue(since <= UNIT, log.events.get(i) + " " + since);
                    }
                }
                assertEquals(r.commands(), log.events.stream().filter(e -> !e.equals("arrived") && !e.equals("gripped"))
                        .count(), what);
                if (policy == ControlPolicy.EAGER) {
                    assertEquals(0, log.times.get(0), "eager: move at once");
                }
            }
        }
    }

    @Test
    void aStallingArmRaisesTheAlarmWithinTheBoundAndTheSafeActionIsTaken() throws Exception {
        Network arm = load("robot-arm.xta");
        TestInterface names = TestInterface.fromNames(arm);
        Mutant stalling = Mutants.derive(arm, names, Duration.ofSeconds(10)).stream()
                .filter(m -> m.kind() == Mutant.Kind.OUTPUT_DROPPED && m.change().contains("o_arrived"))
                .findFirst().orElseThrow();
        for (SafeAction safe : List.of(SafeAction.channel("i_stop"), SafeAction.location("Controller.Safe"))) {
            for (long seed = 1; seed <= 10; seed++) {
                Log log = new Log();
                RecordingPlant plant = new RecordingPlant(new ModelSystem(stalling.network(), names, seed));
                ControlResult r = new Controller(arm, names, plant, options(seed, 200))
                        .policy(ControlPolicy.RANDOM, List.of()).safeAction(safe).addListener(log).run();
                String what = safe + " seed " + seed + ": " + r;
                assertEquals(ControlResult.Outcome.ALARM, r.outcome(), what);
                assertEquals(1, r.alarms(), what);
                assertEquals(List.of("move"), log.events, what);
                long move = log.times.get(0);
                // the bound: arrived within 5 units of move; a stall is known once the bound has passed, one tick on
                assertEquals(move + 5 * UNIT + TICK, r.alarmMicros(), what);
                assertEquals(r.alarmMicros(), log.alarmMicros, what);
                assertTrue(r.reason().startsWith("no reading came by t=" + (move / UNIT + 5) + "."), what);
                assertEquals("stop()", r.safeAction(), what);
                assertEquals(List.of("move@" + move, "stop@" + r.alarmMicros()), plant.given, what);
                assertEquals(2, r.commands(), what);
            }
        }
    }

    @Test
    void withoutASafeActionTheAlarmStopsTheRunWithTheReason() throws Exception {
        Network arm = load("robot-arm.xta");
        TestInterface names = TestInterface.fromNames(arm);
        Mutant stalling = Mutants.derive(arm, names, Duration.ofSeconds(10)).stream()
                .filter(m -> m.kind() == Mutant.Kind.OUTPUT_DROPPED && m.change().contains("o_gripped"))
                .findFirst().orElseThrow();
        RecordingPlant plant = new RecordingPlant(new ModelSystem(stalling.network(), names, 7));
        ControlResult r = new Controller(arm, names, plant, options(7, 200)).run();
        assertEquals(ControlResult.Outcome.ALARM, r.outcome(), r.toString());
        assertNull(r.safeAction());
        assertTrue(r.reason().contains("gripped between") && r.reason().endsWith("the model declares no safe action:"
                + " the controller stopped"), r.reason());
        assertEquals(List.of("move", "grip"), plant.given.stream().map(g -> g.substring(0, g.indexOf('@'))).toList());
    }

    @Test
    void aVersionWhoseQueriesHoldIsTakenAtAResetPointMidRun() throws Exception {
        Network arm = load("robot-arm.xta");
        TestInterface names = TestInterface.fromNames(arm);
        Network v2 = load("robot-arm-v2.xta");
        ModelVersion.Check check = ModelVersion.check(new ModelVersion("robot-arm-v2.xta", v2,
                TestInterface.fromNames(v2)), names, queries());
        assertTrue(check.accepted(), check.refusal());
        Log log = new Log();
        Controller controller = new Controller(arm, names, new ModelSystem(arm, names, 11), options(11, 200));
        controller.addListener(log).addListener(new ControlListener() {
            @Override
            public void readingTaken(Event reading, long micros) {
                if (reading.channel().equals("arrived") && log.taken.isEmpty()) {
                    controller.offer(check); // handed in mid-cycle: taken after the release that ends it
                }
            }
        });
        ControlResult r = controller.run();
        assertEquals(ControlResult.Outcome.COMPLETED, r.outcome(), r.toString());
        assertEquals(1, log.taken.size(), log.taken.toString());
        long at = Long.parseLong(log.taken.get(0).substring(log.taken.get(0).indexOf('@') + 1));
        int release = log.events.indexOf("release");
        assertEquals(log.times.get(release), at, "taken at the first reset point: right after the first release");
        assertEquals(List.of("robot-arm-v2.xta at t=" + at / UNIT + "." + String.format("%03d", at % UNIT)),
                r.versions());
        for (int i = 0; i < log.events.size(); i++) {
            if (log.events.get(i).equals("release")) {
                long held = log.times.get(i) - log.lastBefore("gripped", i);
                long hold = log.times.get(i) > at ? 5 : 3; // version 2 holds a part 5 units, the first 3
                assertEquals(hold * UNIT, held, "release " + i + " of " + log.events);
            }
        }
        assertTrue(log.events.subList(release + 1, log.events.size()).contains("release"), "v2 released a part too");
    }

    @Test
    void aVersionWhoseQueryFailsIsRefusedAndTheRunGoesOnWithTheOldOne() throws Exception {
        Network arm = load("robot-arm.xta");
        TestInterface names = TestInterface.fromNames(arm);
        Network slow = load("robot-arm-slow.xta");
        ModelVersion.Check check = ModelVersion.check(new ModelVersion("robot-arm-slow.xta", slow,
                TestInterface.fromNames(slow)), names, queries());
        assertFalse(check.accepted());
        assertEquals("query [2] A[] (Arm.Moving imply Arm.y <= 5) is NOT satisfied", check.refusal());
        Log log = new Log();
        List<String> refused = new ArrayList<>();
        Controller controller = new Controller(arm, names, new ModelSystem(arm, names, 5), options(5, 100));
        controller.addListener(log).addListener(new ControlListener() {
            @Override
            public void versionRefused(String version, String reason) {
                refused.add(version + ": " + reason);
            }

            @Override
            public void readingTaken(Event reading, long micros) {
                if (refused.isEmpty()) {
                    controller.offer(check);
                }
            }
        });
        ControlResult r = controller.run();
        assertEquals(ControlResult.Outcome.COMPLETED, r.outcome(), r.toString());
        assertEquals(List.of("robot-arm-slow.xta: query [2] A[] (Arm.Moving imply Arm.y <= 5) is NOT satisfied"),
                refused);
        assertEquals(refused, r.refused());
        assertTrue(r.versions().isEmpty());
        for (int i = 0; i < log.events.size(); i++) {
            if (log.events.get(i).equals("release")) {
                assertEquals(3 * UNIT, log.times.get(i) - log.lastBefore("gripped", i), "the old version's hold");
            }
        }
    }

    @Test
    void aVersionWithOtherCommandsIsRefused() throws Exception {
        Network arm = load("robot-arm.xta");
        Network other = ModelLoader.load("other.xta", "chan i_move, o_arrived;\nprocess P() { state A; init A;"
                + " trans A -> A { sync i_move!; }, A -> A { sync o_arrived?; }; }\nprocess Q() { state B; init B;"
                + " trans B -> B { sync i_move?; }, B -> B { sync o_arrived!; }; }\nsystem P, Q;");
        ModelVersion.Check check = ModelVersion.check(new ModelVersion("other.xta", other,
                TestInterface.fromNames(other)), TestInterface.fromNames(arm), queries());
        assertEquals("its commands [move] are not the running version's [grip, move, release, stop]", check.refusal());
        ModelVersion.Check noQueries = ModelVersion.check(new ModelVersion("robot-arm.xta", arm,
                TestInterface.fromNames(arm)), TestInterface.fromNames(arm), List.of());
        assertTrue(noQueries.refusal().startsWith("it has no queries"), noQueries.refusal());
    }
}
