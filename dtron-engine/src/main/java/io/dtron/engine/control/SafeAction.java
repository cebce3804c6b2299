package io.dtron.engine.control;

import io.dtron.model.Edge;
import io.dtron.model.Expression;
import io.dtron.model.Network;
import io.dtron.model.TestInterface;
import java.util.LinkedHashSet;
import java.util.Optional;
import java.util.Set;

/**
 * What the controller does after an alarm: send a command the model declares safe ({@code i_stop}), or the command
 * that leads the model's controller into a location declared safe ({@code Arm.safe}: the one command its edges into
 * that location send); or nothing, when the model has none: then the run stops with the reason.
 *
 * @param channel  the safe command's channel ({@code i_stop} or {@code stop}), or null
 * @param location the safe location as {@code PROCESS.LOCATION}, or null
 */
public record SafeAction(String channel, String location) {
    /** No safe action: an alarm stops the run. */
    public static final SafeAction NONE = new SafeAction(null, null);

    public SafeAction {
        if (channel != null && location != null) {
            throw new IllegalArgumentException("a safe action is a channel or a location, not both");
        }
    }

    /** The safe command on {@code channel} ({@code i_stop} or {@code stop}). */
    public static SafeAction channel(String channel) {
        return new SafeAction(channel, null);
    }

    /** The command into the safe location {@code processDotLocation} ({@code Arm.safe}). */
    public static SafeAction location(String processDotLocation) {
        return new SafeAction(null, processDotLocation);
    }

    /**
     * The command channel of this safe action in {@code network}, or empty for {@link #NONE}.
     *
     * @throws IllegalArgumentException naming what is wrong: no such input, process or location, or a location that
     *                                  no single command leads into
     */
    public Optional<TestInterface.ObservableChannel> resolve(Network network, TestInterface testInterface) {
        if (channel != null) {
            return Optional.of(input(testInterface, channel).orElseThrow(() -> new IllegalArgumentException(
                    "the safe action " + channel + " is no input (command) of the model; its inputs are "
                            + testInterface.inputs().stream().map(TestInterface.ObservableChannel::modelName).toList())));
        }
        if (location == null) {
            return Optional.empty();
        }
        int dot = location.lastIndexOf('.');
        if (dot <= 0 || dot == location.length() - 1) {
            throw new IllegalArgumentException("the safe location " + location + " is not PROCESS.LOCATION");
        }
        String processName = location.substring(0, dot);
        io.dtron.model.Process process = network.process(processName).orElseThrow(() -> new IllegalArgumentException(
                "the safe location " + location + ": the model has no process " + processName));
        io.dtron.model.Location target = process.location(location.substring(dot + 1));
        if (target == null) {
            throw new IllegalArgumentException("the safe location " + location + ": " + processName + " has no location "
                    + location.substring(dot + 1));
        }
        Set<String> commands = new LinkedHashSet<>();
        for (Edge e : process.edges()) {
            if (e.target() == target.index() && e.sync() != null && e.sync().direction() == Edge.Direction.SEND
                    && e.sync().channel() instanceof Expression.ChannelRef ref) {
                String name = ref.channel().name();
                if (testInterface.inputs().stream().anyMatch(c -> c.modelName().equals(name))) {
                    commands.add(name);
                }
            }
        }
        if (commands.size() != 1) {
            throw new IllegalArgumentException("the safe location " + location + " must be entered by edges that send"
                    + " one command, the safe action; " + (commands.isEmpty() ? "no edge into it sends a command"
                    : "its edges send " + commands));
        }
        return input(testInterface, commands.iterator().next());
    }

    private static Optional<TestInterface.ObservableChannel> input(TestInterface testInterface, String name) {
        return testInterface.inputs().stream().filter(c -> c.modelName().equals(name) || c.name().equals(name))
                .findFirst();
    }

    @Override
    public String toString() {
        return channel != null ? channel : location != null ? location : "none";
    }
}
