package io.dtron.xta.ast;

import io.dtron.xta.Pos;
import java.util.List;

/**
 * A TRON interface file ({@code .trn}): {@code input grasp(), release(); output level(adapLevel);
 * precision 1000; timeout 1000;}.
 *
 * @param inputs    the input channels with their attached variables
 * @param outputs   the output channels with their attached variables
 * @param precision the time unit in microseconds, or null when not given
 * @param timeout   the test timeout in model time units, or null when not given
 */
public record InterfaceSpec(List<Channel> inputs, List<Channel> outputs, Long precision, Long timeout) {
    public InterfaceSpec {
        inputs = List.copyOf(inputs);
        outputs = List.copyOf(outputs);
    }

    /** A channel with the global integer variables attached to it. */
    public record Channel(Pos pos, String name, List<Variable> variables) {
        public Channel {
            variables = List.copyOf(variables);
        }
    }

    /** A variable name attached to a channel. */
    public record Variable(Pos pos, String name) {
    }
}
