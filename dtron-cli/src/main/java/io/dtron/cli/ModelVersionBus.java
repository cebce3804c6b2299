package io.dtron.cli;

import io.dtron.api.Dtron;
import io.dtron.api.DtronException;
import io.dtron.api.DtronListener;
import io.dtron.api.IDtronChannelValued;
import io.dtron.engine.control.ControlListener;
import io.dtron.engine.control.ControlResult;
import io.dtron.engine.control.Controller;
import io.dtron.engine.control.ModelVersion;
import io.dtron.model.ModelLoader;
import io.dtron.model.TestInterface;
import java.nio.charset.StandardCharsets;
import java.nio.file.Path;
import java.util.LinkedHashMap;
import java.util.Map;
import java.util.concurrent.ArrayBlockingQueue;
import java.util.concurrent.RejectedExecutionException;
import java.util.concurrent.ThreadPoolExecutor;
import java.util.concurrent.TimeUnit;
import org.slf4j.Logger;
import org.slf4j.LoggerFactory;

/**
 * The model versions of {@code dtron control --reload-from-bus}: messages on {@link Dtron#MODEL_VERSION}, each a JSON
 * object with the version's {@code model} text (an {@code .xml} or {@code .xta} model), its {@code queries} (the text
 * of its {@code .q}, optional) and a {@code label} (optional). Each is loaded and checked as a version of {@code
 * --reload-from} is ({@link ModelVersionFile#check}), on a thread of its own (never the bus's), and handed to the
 * controller; what became of it is published on {@link Dtron#MODEL_OUTCOME} with the message's {@code version}:
 * refused with the reason, accepted (waits for the next reset point), taken at a reset point, or refused when a later
 * version replaced it or the run ended first. Nothing in a message is executed: the model is parsed and model-checked.
 * A message larger than {@value #MAX_TEXT_BYTES} bytes, or malformed, is refused and counted with the others.
 */
final class ModelVersionBus implements ControlListener, AutoCloseable {
    /** The largest model version taken from the bus, in bytes of UTF-8: NATS carries messages of up to 1 MB. */
    static final int MAX_TEXT_BYTES = 512 * 1024;
    /** How many versions may wait for their check; more are refused. */
    private static final int WAITING = 4;

    private static final Logger LOG = LoggerFactory.getLogger(ModelVersionBus.class);

    private final Dtron bus;
    private final Controller controller;
    private final Path started;
    private final Path interfaceFile;
    private final TestInterface running;
    private final long unit;
    private final ThreadPoolExecutor checking = new ThreadPoolExecutor(1, 1, 0, TimeUnit.SECONDS,
            new ArrayBlockingQueue<>(WAITING), r -> {
                Thread thread = new Thread(r, "dtron-model-versions-bus");
                thread.setDaemon(true);
                return thread;
            });
    /** The versions accepted and not yet taken: label to the sender's number. */
    private final Map<String, Integer> waiting = new LinkedHashMap<>();
    private final DtronListener listener = new DtronListener(Dtron.MODEL_VERSION) {
        @Override
        public void messageReceived(IDtronChannelValued message) {
            received(message);
        }
    };

    /**
     * Versions from {@code bus} for {@code controller}, which runs the model {@code started} (its interface {@code
     * running}, from {@code interfaceFile} when not null), at {@code unit} microseconds a time unit.
     */
    ModelVersionBus(Dtron bus, Controller controller, Path started, Path interfaceFile, TestInterface running,
            long unit) {
        this.bus = bus;
        this.controller = controller;
        this.started = started;
        this.interfaceFile = interfaceFile;
        this.running = running;
        this.unit = unit;
    }

    /** Starts listening; the controller tells this which versions it took. */
    void listen() {
        controller.addListener(this);
        bus.addDtronListener(listener);
    }

    /** On the bus's thread: only hands the message on. */
    private void received(IDtronChannelValued message) {
        int version = message.getVariables().getOrDefault("version", 0);
        String label = "bus version " + version + " from " + message.getSender();
        String text = message.getText();
        try {
            checking.execute(() -> check(version, label, text));
        } catch (RejectedExecutionException e) {
            refused(version, label, WAITING + " versions wait for their check already");
        }
    }

    private void check(int version, String label, String text) {
        if (text.getBytes(StandardCharsets.UTF_8).length > MAX_TEXT_BYTES) {
            refused(version, label, "it is larger than " + MAX_TEXT_BYTES + " bytes");
            return;
        }
        Map<?, ?> fields;
        try {
            if (!(Json.parse(text) instanceof Map<?, ?> object)) {
                throw new IllegalArgumentException("not a JSON object");
            }
            fields = object;
            for (Object key : fields.keySet()) {
                if (!key.equals("label") && !key.equals("model") && !key.equals("queries")) {
                    throw new IllegalArgumentException("unknown field '" + key + "' (label, model, queries)");
                }
                if (!(fields.get(key) instanceof String)) {
                    throw new IllegalArgumentException("'" + key + "' is not a string");
                }
            }
            if (!fields.containsKey("model")) {
                throw new IllegalArgumentException("no 'model'");
            }
        } catch (IllegalArgumentException e) {
            refused(version, label, "malformed: " + e.getMessage());
            return;
        }
        String named = fields.containsKey("label") ? fields.get("label") + " (" + label + ")" : label;
        String model = (String) fields.get("model");
        ModelVersionFile.check(named, () -> ModelLoader.load(named, model), (String) fields.get("queries"), started,
                interfaceFile, running, new ModelVersionFile.Sink() {
                    @Override
                    public void checked(ModelVersion.Check check) {
                        if (!check.accepted()) {
                            refused(version, named, check.refusal());
                            return;
                        }
                        synchronized (waiting) {
                            waiting.forEach((other, number) -> publish(number, 2, "model version " + other
                                    + " refused: " + named + " replaced it before a reset point"));
                            waiting.clear();
                            waiting.put(named, version);
                            publish(version, 1, "model version " + named + " accepted: it is taken at the next reset"
                                    + " point");
                            controller.offer(check);
                        }
                    }

                    @Override
                    public void unloadable(String name, String reason) {
                        refused(version, name, reason);
                    }
                });
    }

    /** Refuses the version: told to the controller (which counts it) and to the sender. */
    private void refused(int version, String label, String reason) {
        controller.refuse(label, reason);
        publish(version, 2, "model version " + label + " refused: " + reason);
    }

    @Override
    public void versionTaken(String version, long micros) {
        synchronized (waiting) {
            Integer number = waiting.remove(version);
            if (number != null) {
                publish(number, 0, "model version " + version + " taken at " + ControlResult.time(micros, unit)
                        + " (a reset point)");
            }
        }
    }

    private void publish(int version, int outcome, String text) {
        try {
            bus.send(Dtron.MODEL_OUTCOME.constructValued(Map.of("version", version, "outcome", outcome)), text);
        } catch (DtronException | IllegalStateException e) {
            LOG.warn("Cannot publish the outcome of model version {}: {}", version, e.getMessage());
        }
    }

    /** The run is over: versions still waiting for a reset point are refused, and the bus is left alone. */
    @Override
    public void close() {
        bus.removeDtronListener(listener);
        checking.shutdownNow();
        synchronized (waiting) {
            waiting.forEach((label, number) -> publish(number, 2, "model version " + label + " refused: the run"
                    + " ended before a reset point"));
            waiting.clear();
        }
    }
}
