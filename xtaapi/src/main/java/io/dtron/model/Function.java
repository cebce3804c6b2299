package io.dtron.model;

import io.dtron.xta.Pos;
import java.util.List;

/**
 * A user function: global, or one copy per process for functions declared in a template.
 *
 * @param index          its number in {@link Network#functions()}
 * @param name           the qualified name ({@code enqueue} or {@code Gate.enqueue})
 * @param owner          the owning process's name, or null
 * @param returnType     the return type
 * @param parameters     the parameters, each in its frame slot
 * @param frameSize      the number of frame slots the function needs (parameters and locals)
 * @param body           the body
 * @param sideEffectFree whether it changes nothing outside its own frame (so it may be used in guards)
 * @param pos            where it was declared
 */
public record Function(int index, String name, String owner, Type returnType, List<Parameter> parameters,
                       int frameSize, Statement.Block body, boolean sideEffectFree, Pos pos) {
    public Function {
        parameters = List.copyOf(parameters);
    }

    /** A parameter: by value (its slots hold the value) or by reference (its slot holds a location). */
    public record Parameter(String name, Type type, boolean reference, int slot) {
    }
}
