package io.dtron.cli;

import static org.junit.jupiter.api.Assertions.assertEquals;
import static org.junit.jupiter.api.Assertions.assertTrue;

import io.dtron.api.Dtron;
import io.dtron.api.DtronOptions;
import io.dtron.api.IDtronChannelValued;
import io.dtron.engine.TestOptions;
import io.dtron.engine.control.ControlListener;
import io.dtron.engine.control.Controller;
import io.dtron.engine.sim.ModelSystem;
import io.dtron.model.ModelLoader;
import io.dtron.model.Network;
import io.dtron.model.TestInterface;
import io.dtron.testsupport.Inbox;
import io.dtron.testsupport.NatsServer;
import java.nio.charset.StandardCharsets;
import java.nio.file.Files;
import java.nio.file.Path;
import java.time.Duration;
import java.util.List;
import java.util.Map;
import java.util.concurrent.CopyOnWriteArrayList;
import org.junit.jupiter.api.Test;
import org.junit.jupiter.api.Timeout;
import org.junit.jupiter.api.io.TempDir;

/**
 * The model versions a controller takes from the bus ({@code --reload-from-bus}), on an in-JVM bus with the robot-arm
 * sample, the controller not running: every message is answered on {@code dtron_model_outcome} with its number. A
 * message too large, not a JSON object of strings, with an unknown field or without a model, or whose model does not
 * load, is refused with the reason and counted; a version that keeps the sample's queries is accepted, then taken when
 * the controller says so; one accepted and still waiting when the run ends is refused then. On an in-JVM bus and on
 * NATS (skipped without nats-server, as the other NATS tests).
 */
@Timeout(60)
class ModelVersionBusTest {
    private static final Path SAMPLE = Path.of("../models/src/main/resources/io/dtron/models/robotarm");

    private static String json(String label, Path model) throws Exception {
        return "{\"label\": " + JsonTrace.quote(label) + ", \"model\": "
                + JsonTrace.quote(Files.readString(model, StandardCharsets.UTF_8)) + "}";
    }

    @Test
    void everyVersionIsAnsweredRefusedOnesWithTheirReasonAndCounted() throws Exception {
        String cluster = "versions-" + ProcessHandle.current().pid() + "-" + System.nanoTime();
        try (Dtron controllerMember = Dtron.connect(DtronOptions.builder().clusterName(cluster).inJvm(true).build());
                Dtron sender = Dtron.connect(DtronOptions.builder().clusterName(cluster).inJvm(true).build())) {
            answered(controllerMember, sender);
        }
    }

    /** The same on a NATS bus, whose messages carry the bus's code over the whole message, the text included. */
    @Test
    void overNatsAsWell(@TempDir Path dir) throws Exception {
        String cluster = "versions-" + ProcessHandle.current().pid();
        try (NatsServer server = NatsServer.start(dir);
                Dtron controllerMember = Dtron.connect(DtronOptions.builder().clusterName(cluster)
                        .natsServers(server.url()).build());
                Dtron sender = Dtron.connect(DtronOptions.builder().clusterName(cluster).natsServers(server.url())
                        .build())) {
            answered(controllerMember, sender);
        }
    }

    private static void answered(Dtron controllerMember, Dtron sender) throws Exception {
        Path arm = SAMPLE.resolve("robot-arm.xta");
        Network network = ModelLoader.load(arm);
        TestInterface testInterface = TestInterface.fromNames(network);
        Controller controller = new Controller(network, testInterface, new ModelSystem(network, testInterface, 1),
                TestOptions.defaults(1).withTimeout(10).withVirtualTime(true));
        List<String> refusedByController = new CopyOnWriteArrayList<>();
        controller.addListener(new ControlListener() {
            @Override
            public void versionRefused(String version, String reason) {
                refusedByController.add(reason);
            }
        });
        assertTrue(sender.awaitMembers(2, Duration.ofSeconds(30)));
        Inbox outcomes = new Inbox(Dtron.MODEL_OUTCOME);
        sender.addDtronListener(outcomes);
        ModelVersionBus versions = new ModelVersionBus(controllerMember, controller, arm, null, testInterface,
                1000);
        versions.listen();
        String from = " (bus version %d from " + sender.getMemberId() + ")";

        List<String> messages = List.of("x".repeat(ModelVersionBus.MAX_TEXT_BYTES + 1), "chan i_move;",
                "{\"model\": \"chan i_move;\", \"run\": \"rm -rf /\"}", "{\"label\": \"v\"}",
                "{\"model\": 3}", "{\"label\": \"broken\", \"model\": \"chan i_move;;\"}",
                json("slow", SAMPLE.resolve("robot-arm-slow.xta")));
        List<String> reasons = List.of("it is larger than 524288 bytes", "malformed: ", "malformed: unknown field"
                + " 'run' (label, model, queries)", "malformed: no 'model'", "malformed: 'model' is not a string",
                "it does not load: broken", "query [2] A[] (Arm.Moving imply Arm.y <= 5) is NOT satisfied");
        for (int i = 0; i < messages.size(); i++) {
            sender.send(Dtron.MODEL_VERSION.constructValued(Map.of("version", i + 1)), messages.get(i));
            IDtronChannelValued outcome = outcomes.take();
            assertEquals(Map.of("version", i + 1, "outcome", 2), outcome.getVariables(), outcome.getText());
            assertTrue(outcome.getText().contains(" refused: " + reasons.get(i)), outcome.getText());
        }
        assertEquals(messages.size(), refusedByController.size(), "each refusal is counted: "
                + refusedByController);

        sender.send(Dtron.MODEL_VERSION.constructValued(Map.of("version", 20)), json("v2",
                SAMPLE.resolve("robot-arm-v2.xta")));
        IDtronChannelValued accepted = outcomes.take();
        String v2 = "v2" + String.format(from, 20);
        assertEquals(Map.of("version", 20, "outcome", 1), accepted.getVariables(), accepted.getText());
        assertEquals("model version " + v2 + " accepted: it is taken at the next reset point", accepted.getText());
        versions.versionTaken(v2, 7_500);
        IDtronChannelValued taken = outcomes.take();
        assertEquals(Map.of("version", 20, "outcome", 0), taken.getVariables(), taken.getText());
        assertEquals("model version " + v2 + " taken at t=7.500 (a reset point)", taken.getText());

        sender.send(Dtron.MODEL_VERSION.constructValued(Map.of("version", 21)), json("v2",
                SAMPLE.resolve("robot-arm-v2.xta")));
        assertEquals(1, outcomes.take().getVariables().get("outcome"));
        versions.close();
        IDtronChannelValued ended = outcomes.take();
        assertEquals(Map.of("version", 21, "outcome", 2), ended.getVariables(), ended.getText());
        assertEquals("model version v2" + String.format(from, 21) + " refused: the run ended before a reset point",
                ended.getText());
    }
}
