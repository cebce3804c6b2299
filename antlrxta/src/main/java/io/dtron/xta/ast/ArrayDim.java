package io.dtron.xta.ast;

import io.dtron.xta.Pos;

/**
 * One array dimension, {@code [size]} or {@code [type]}: exactly one of {@code size} and {@code type} is set.
 * A bare name in brackets is parsed as a size; name resolution decides whether it names a type.
 */
public record ArrayDim(Pos pos, Expr size, TypeExpr type) {
}
