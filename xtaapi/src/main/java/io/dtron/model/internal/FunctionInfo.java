package io.dtron.model.internal;

import io.dtron.model.Function;
import io.dtron.model.Type;
import java.util.List;

/** A function's signature and, once compiled, whether it is free of side effects. */
final class FunctionInfo {
    final int index;
    final String name;
    final Type returnType;
    final List<Function.Parameter> parameters;
    boolean sideEffectFree = true;

    FunctionInfo(int index, String name, Type returnType, List<Function.Parameter> parameters) {
        this.index = index;
        this.name = name;
        this.returnType = returnType;
        this.parameters = List.copyOf(parameters);
    }
}
