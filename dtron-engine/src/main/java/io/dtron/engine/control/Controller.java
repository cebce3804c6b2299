package io.dtron.engine.control;

import io.dtron.engine.Adapter;
import io.dtron.engine.TestOptions;
import io.dtron.engine.UnsupportedModelException;
import io.dtron.engine.internal.control.ControlLoop;
import io.dtron.model.Network;
import io.dtron.model.TestInterface;
import java.util.List;
import java.util.Objects;
import java.util.concurrent.CopyOnWriteArrayList;
import java.util.concurrent.atomic.AtomicReference;

/**
 * The model as controller. The engine executes the controller part of a closed model (the environment side of its
 * interface: the {@code i_} channels are commands it chooses and sends) against a plant (the {@link Adapter}: its
 * {@code o_} channels are sensor readings), following the set of states the model may be in, as the online tester
 * does, on the same clocks (virtual or real time, {@link TestOptions#virtualTime()}). Commands and their times are
 * chosen by a {@link ControlPolicy}. Unlike the tester, a plant that deviates from the model (a reading the model
 * does not allow then, or none by a deadline) is no verdict but an alarm: the controller then sends the model's
 * {@link SafeAction safe action}, if it has one, and the run ends. A run lasts {@link TestOptions#timeout()} time
 * units. A new {@link ModelVersion} handed in during the run ({@link #offer}) is taken at the next reset point: a
 * moment when the run is back in the initial state of the model it runs (every process at its initial location,
 * every variable at its initial value), the new version starting from its own initial state there.
 */
public final class Controller {
    private final Network network;
    private final TestInterface testInterface;
    private final Adapter plant;
    private final TestOptions options;
    private final List<ControlListener> listeners = new CopyOnWriteArrayList<>();
    private final AtomicReference<ModelVersion> offered = new AtomicReference<>();
    private final List<String> refused = new CopyOnWriteArrayList<>();
    private ControlPolicy policy = ControlPolicy.EAGER;
    private List<String> goals = List.of();
    private SafeAction safeAction = SafeAction.NONE;

    /** A controller running {@code network} against {@code plant}, for {@code options.timeout()} time units. */
    public Controller(Network network, TestInterface testInterface, Adapter plant, TestOptions options) {
        this.network = Objects.requireNonNull(network, "network");
        this.testInterface = Objects.requireNonNull(testInterface, "testInterface");
        this.plant = Objects.requireNonNull(plant, "plant");
        this.options = Objects.requireNonNull(options, "options");
    }

    /**
     * How commands are chosen; {@code goals} ({@code E<> p} queries) for {@link ControlPolicy#GOAL}, which needs at
     * least one.
     *
     * @throws IllegalArgumentException when the goal policy has no goal, or goals are given to another policy
     */
    public Controller policy(ControlPolicy policy, List<String> goals) {
        Objects.requireNonNull(policy, "policy");
        if (policy == ControlPolicy.GOAL && goals.isEmpty()) {
            throw new IllegalArgumentException("the goal policy needs at least one goal (E<> p)");
        }
        if (policy != ControlPolicy.GOAL && !goals.isEmpty()) {
            throw new IllegalArgumentException("goals steer only the goal policy, not the "
                    + policy.name().toLowerCase(java.util.Locale.ROOT) + " one");
        }
        this.policy = policy;
        this.goals = List.copyOf(goals);
        return this;
    }

    /**
     * The safe action taken after an alarm.
     *
     * @throws IllegalArgumentException when it is no command of the model, or names a location no single command
     *                                  leads into
     */
    public Controller safeAction(SafeAction action) {
        Objects.requireNonNull(action, "action").resolve(network, testInterface);
        this.safeAction = action;
        return this;
    }

    /** Adds a listener that follows the run. */
    public Controller addListener(ControlListener listener) {
        listeners.add(Objects.requireNonNull(listener, "listener"));
        return this;
    }

    /**
     * Hands in a model version (thread-safe, before or during the run): a refused {@link ModelVersion.Check} is told
     * to the listeners and changes nothing; an accepted one is taken at the next reset point (replacing one handed in
     * before and not yet taken).
     */
    public void offer(ModelVersion.Check check) {
        Objects.requireNonNull(check, "check");
        if (!check.accepted()) {
            refuse(check.version().label(), check.refusal());
            return;
        }
        offered.set(check.version());
    }

    /**
     * Records a version refused before it could be checked ({@code reason}: it does not load, its queries cannot be
     * read): told to the listeners and counted in the result, as a refused {@link #offer} is (thread-safe).
     */
    public void refuse(String version, String reason) {
        refused.add(Objects.requireNonNull(version, "version") + ": " + Objects.requireNonNull(reason, "reason"));
        for (ControlListener l : listeners) {
            l.versionRefused(version, reason);
        }
    }

    /**
     * Runs to the end of its duration, an alarm, or what stops it.
     *
     * @throws UnsupportedModelException when the model cannot be run or its interface does not split it into a
     *                                   controller and a plant
     * @throws io.dtron.engine.verify.QueryException when a goal of the goal policy does not compile
     */
    public ControlResult run() {
        return new ControlLoop(network, testInterface, plant, options, policy, goals,
                safeAction, listeners, offered, refused).run();
    }
}
