package io.dtron.model;

import java.util.function.ToIntFunction;

/** Names of array elements, as the model writes them. */
final class Names {
    private Names() {
    }

    static String element(String name, Type type, int relative, ToIntFunction<Type> size) {
        StringBuilder sb = new StringBuilder(name);
        Type t = type;
        int rest = relative;
        while (t instanceof Type.Array a) {
            int elementSize = size.applyAsInt(a.element());
            int i = elementSize == 0 ? 0 : rest / elementSize;
            rest -= i * elementSize;
            sb.append('[').append(a.firstIndex() + i).append(']');
            t = a.element();
        }
        return sb.toString();
    }
}
