package io.dtron.api;

import io.dtron.api.internal.DtronChannel;
import java.util.Collection;
import java.util.List;
import java.util.Map;

/**
 * A channel template: the channel's name and the names of its variables.
 * Immutable; two templates are equal when their names and variable lists are.
 */
public interface IDtronChannel extends IChannelSkeleton {

    /** Returns the variable names, in declaration order; immutable. */
    List<String> getVariableNames();

    /**
     * Creates a message of this channel.
     *
     * @param values a value for every variable of the template and for no other name
     * @throws InvalidMessageException if a name is unknown or a variable has no value
     *                                 ({@link InvalidMessageException.Reason#UNKNOWN_VARIABLES},
     *                                 {@link InvalidMessageException.Reason#MISSING_VARIABLES})
     */
    IDtronChannelValued constructValued(Map<String, Integer> values);

    /**
     * Decodes a {@code Sync} protocol-buffer message of this channel.
     *
     * @throws InvalidMessageException if the bytes are no valid Sync, name another channel, or
     *                                 carry unknown or missing variables
     */
    IDtronChannelValued constructValued(byte[] message);

    /**
     * Creates a template.
     *
     * @param channelName   the bus channel name, an identifier ({@code [A-Za-z_][A-Za-z0-9_]*})
     * @param variableNames distinct identifiers
     * @throws IllegalArgumentException if a name is no identifier or a variable name repeats
     */
    static IDtronChannel of(String channelName, String... variableNames) {
        return new DtronChannel(channelName, List.of(variableNames));
    }

    /**
     * Creates a template.
     *
     * @see #of(String, String...)
     */
    static IDtronChannel of(String channelName, Collection<String> variableNames) {
        return new DtronChannel(channelName, List.copyOf(variableNames));
    }

    /**
     * Creates the template of a model channel with the model's naming:
     * the {@code i_}/{@code o_} prefix is dropped from the channel and
     * {@code <modelChannel>_} from each attached variable.
     * {@code fromModel("i_move", List.of("i_move_amount"))} is
     * {@code of("move", "amount")}; a name without these prefixes stays as it
     * is ({@code fromModel("level", List.of("adapLevel"))} is {@code of("level", "adapLevel")}).
     */
    static IDtronChannel fromModel(String modelChannel, Collection<String> attachedVariables) {
        return DtronChannel.fromModel(modelChannel, attachedVariables);
    }
}
