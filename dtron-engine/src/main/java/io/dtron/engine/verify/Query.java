package io.dtron.engine.verify;

import io.dtron.engine.internal.verify.QueryParser;
import java.util.List;
import java.util.Objects;

/**
 * A query as written, split into its path quantifier and its state properties. A query the checker cannot
 * check (statistical, optimisation, strategy queries) is {@link Kind#UNSUPPORTED} with the reason; a line of a
 * {@code .q} file (or a query of the model) that does not parse is {@link Kind#INVALID} with the error.
 *
 * @param text     the query as written, trimmed
 * @param kind     its kind
 * @param property the state property {@code p} (for leads-to: the premise), or null when unsupported
 * @param target   the {@code q} of {@code p --> q}, else null
 * @param reason   why an unsupported query is not checked, or the error of an invalid one, else null
 * @param column   the 1-based column in {@link #text} where {@code property} starts (0 when unsupported)
 * @param line     the 1-based line of a {@code .q} file the query is on, else 0
 */
public record Query(String text, Kind kind, String property, String target, String reason, int column, int line) {

    /** The kinds of query. */
    public enum Kind {
        /** {@code E<> p}: some reachable state satisfies p. */
        EXISTS_EVENTUALLY,
        /** {@code A[] p}: every reachable state satisfies p. */
        ALWAYS_GLOBALLY,
        /** {@code E[] p}: p holds at every instant of some maximal path. */
        EXISTS_GLOBALLY,
        /** {@code A<> p}: every maximal path reaches an instant where p holds. */
        ALWAYS_EVENTUALLY,
        /** {@code p --> q}: from every reachable valuation where p holds, every maximal path reaches q. */
        LEADS_TO,
        /** A query the checker does not check; see {@link Query#reason()}. */
        UNSUPPORTED,
        /** A query that does not parse; {@link Query#reason()} is the error, with its line and column. */
        INVALID
    }

    public Query {
        Objects.requireNonNull(text, "text");
        Objects.requireNonNull(kind, "kind");
    }

    /**
     * Parses one query.
     *
     * @throws QueryException when it is neither a query the checker checks nor one it knows to skip
     */
    public static Query parse(String text) {
        return QueryParser.parse(text);
    }

    /**
     * Parses a {@code .q} file: one query per line; {@code //} and {@code /* *}{@code /} comments and blank
     * lines are ignored. A line that does not parse is an {@link Kind#INVALID} query whose reason names the line
     * and the column, so that the others can still be checked.
     */
    public static List<Query> parseFile(String fileText) {
        return QueryParser.parseFile(fileText);
    }
}
