package io.dtron.xta.ast;

import io.dtron.xta.Pos;
import java.util.List;

/** A parameter of a template, a partial instantiation or a function. */
public record Param(Pos pos, TypeExpr type, boolean reference, String name, List<ArrayDim> dims) {
    public Param {
        dims = List.copyOf(dims);
    }
}
