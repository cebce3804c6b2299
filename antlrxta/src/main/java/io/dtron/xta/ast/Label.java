package io.dtron.xta.ast;

/** The raw text of a label with its drawing position (null when the model has none). */
public record Label(String kind, String text, Coord coord) {
}
