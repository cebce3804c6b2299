package io.dtron.model;

import io.dtron.xta.Diagnostic;
import io.dtron.xta.ModelSyntax;
import io.dtron.xta.Parsed;
import io.dtron.xta.ast.InterfaceSpec;
import java.io.IOException;
import java.nio.file.Files;
import java.nio.file.NoSuchFileException;
import java.nio.file.Path;
import java.util.ArrayList;
import java.util.HashSet;
import java.util.List;
import java.util.Optional;
import java.util.Set;

/**
 * The observable interface of a model: the input channels (the tester offers them to the system under test),
 * the output channels (the system under test produces them), and the global integer variables attached to
 * each, whose values travel with the event. Either taken from names ({@code i_move} is input {@code move},
 * {@code o_done} output {@code done}, a global int {@code i_move_amount} travels with {@code move} as
 * {@code amount}) or from a TRON interface file ({@code .trn}).
 *
 * @param inputs         the input channels
 * @param outputs        the output channels
 * @param timeUnitMicros microseconds per model time unit, or null when the source does not say
 * @param timeout        the test timeout in model time units, or null when the source does not say
 */
public record TestInterface(List<ObservableChannel> inputs, List<ObservableChannel> outputs, Long timeUnitMicros,
                            Long timeout) {
    public TestInterface {
        inputs = List.copyOf(inputs);
        outputs = List.copyOf(outputs);
    }

    /**
     * A channel of the interface.
     *
     * @param name      the name on the bus and in adapters ({@code move} for {@code i_move})
     * @param channel   the channel's number in the network
     * @param modelName the channel's name in the model ({@code i_move}, {@code grasp}, {@code req[1]})
     * @param variables the attached variables, in declaration order
     */
    public record ObservableChannel(String name, int channel, String modelName, List<AttachedVariable> variables) {
        public ObservableChannel {
            variables = List.copyOf(variables);
        }
    }

    /**
     * A global integer variable whose value travels with a channel's events.
     *
     * @param name     the name in messages ({@code amount} for {@code i_move_amount})
     * @param variable the model's variable
     */
    public record AttachedVariable(String name, Variable variable) {
    }

    /** The input called {@code name}. */
    public Optional<ObservableChannel> input(String name) {
        return inputs.stream().filter(c -> c.name().equals(name)).findFirst();
    }

    /** The output called {@code name}. */
    public Optional<ObservableChannel> output(String name) {
        return outputs.stream().filter(c -> c.name().equals(name)).findFirst();
    }

    /** The interface given by names: {@code i_x} channels are inputs, {@code o_y} outputs. */
    public static TestInterface fromNames(Network network) throws ModelException {
        List<ObservableChannel> inputs = new ArrayList<>();
        List<ObservableChannel> outputs = new ArrayList<>();
        List<Diagnostic> errors = new ArrayList<>();
        for (ChannelVariable c : network.channels()) {
            if (c.owner() != null) {
                continue;
            }
            boolean input = c.name().startsWith("i_");
            boolean output = c.name().startsWith("o_");
            if (!input && !output || c.name().length() == 2) {
                continue;
            }
            List<AttachedVariable> attached = new ArrayList<>();
            for (Variable v : network.variables()) {
                if (v.owner() == null && v.name().startsWith(c.name() + "_") && v.name().length() > c.name().length() + 1
                        && !longerChannelClaims(network, c, v)) {
                    if (v.size() != 1 || !v.type().isIntegral()) {
                        errors.add(Diagnostic.error(v.pos(), "'" + v.name() + "' is attached to channel '" + c.name()
                                + "' by its name, so it must be an int or bool, not " + v.type()));
                        continue;
                    }
                    attached.add(new AttachedVariable(v.name().substring(c.name().length() + 1), v));
                }
            }
            String base = c.name().substring(2);
            for (int k = 0; k < c.type().channels(); k++) {
                int index = c.index() + k;
                String modelName = c.elementName(index);
                String name = base + modelName.substring(c.name().length());
                (input ? inputs : outputs).add(new ObservableChannel(name, index, modelName, attached));
            }
        }
        if (!errors.isEmpty()) {
            throw new ModelException(errors);
        }
        return new TestInterface(inputs, outputs, null, null);
    }

    /** Whether a channel with a longer name also prefixes {@code v} (i_a_b_v belongs to i_a_b, not i_a). */
    private static boolean longerChannelClaims(Network network, ChannelVariable c, Variable v) {
        for (ChannelVariable other : network.channels()) {
            if (other != c && other.owner() == null && other.name().length() > c.name().length()
                    && other.name().startsWith(c.name()) && v.name().startsWith(other.name() + "_")) {
                return true;
            }
        }
        return false;
    }

    /** The interface declared in a TRON interface file. */
    public static TestInterface fromFile(Network network, Path file) throws ModelException {
        String text;
        try {
            text = ModelSyntax.decode(Files.readAllBytes(file));
        } catch (NoSuchFileException e) {
            throw new ModelException(List.of(Diagnostic.fileError(file.toString(), "no such file")));
        } catch (IOException e) {
            throw new ModelException(List.of(Diagnostic.fileError(file.toString(), "cannot read: " + e.getMessage())));
        }
        return fromText(network, file.toString(), text);
    }

    /**
     * The interface declared in the text of a TRON interface file; {@code name} is used in messages. A channel array
     * named there gives one channel per element, named as in the model ({@code appr[0]}, {@code appr[1]}, ...), each
     * with the variables attached to the array.
     */
    public static TestInterface fromText(Network network, String name, String text) throws ModelException {
        Parsed<InterfaceSpec> parsed = ModelSyntax.parseInterface(name, text);
        if (parsed.hasErrors()) {
            throw new ModelException(parsed.diagnostics());
        }
        InterfaceSpec spec = parsed.value();
        List<Diagnostic> errors = new ArrayList<>();
        Set<String> seen = new HashSet<>();
        List<ObservableChannel> inputs = resolve(network, spec.inputs(), "input", seen, errors);
        List<ObservableChannel> outputs = resolve(network, spec.outputs(), "output", seen, errors);
        if (spec.precision() != null && spec.precision() <= 0) {
            errors.add(Diagnostic.fileError(name, "precision must be a positive number of microseconds"));
        }
        if (!errors.isEmpty()) {
            throw new ModelException(errors);
        }
        return new TestInterface(inputs, outputs, spec.precision(), spec.timeout());
    }

    private static List<ObservableChannel> resolve(Network network, List<InterfaceSpec.Channel> channels, String kind,
                                                   Set<String> seen, List<Diagnostic> errors) {
        List<ObservableChannel> out = new ArrayList<>();
        for (InterfaceSpec.Channel c : channels) {
            if (!seen.add(c.name())) {
                errors.add(Diagnostic.error(c.pos(), "channel '" + c.name() + "' is declared twice in the interface"));
                continue;
            }
            Optional<ChannelVariable> found = network.channel(c.name()).filter(v -> v.owner() == null);
            if (found.isEmpty()) {
                errors.add(Diagnostic.error(c.pos(), kind + " '" + c.name() + "' is not a global channel of "
                        + network.file()));
                continue;
            }
            List<AttachedVariable> vars = new ArrayList<>();
            for (InterfaceSpec.Variable v : c.variables()) {
                Optional<Variable> var = network.variable(v.name()).filter(x -> x.owner() == null);
                if (var.isEmpty()) {
                    errors.add(Diagnostic.error(v.pos(), "variable '" + v.name() + "' attached to " + kind + " '"
                            + c.name() + "' is not a global variable of " + network.file()));
                } else if (var.get().size() != 1 || !var.get().type().isIntegral()) {
                    errors.add(Diagnostic.error(v.pos(), "variable '" + v.name() + "' attached to " + kind + " '"
                            + c.name() + "' must be an int or bool, not " + var.get().type()));
                } else {
                    vars.add(new AttachedVariable(v.name(), var.get()));
                }
            }
            // an array of channels: one channel per element, named as in the model (appr[0], appr[1], ...)
            ChannelVariable v = found.get();
            for (int k = 0; k < v.type().channels(); k++) {
                String element = v.elementName(v.index() + k);
                out.add(new ObservableChannel(element, v.index() + k, element, vars));
            }
        }
        return out;
    }
}
