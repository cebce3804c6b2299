package io.dtron.xta.ast;

/** A point of the Uppaal editor's drawing, kept so that a model can be written back. */
public record Coord(int x, int y) {
}
