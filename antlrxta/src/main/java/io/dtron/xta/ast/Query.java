package io.dtron.xta.ast;

import io.dtron.xta.Pos;

/**
 * A TCTL query: {@code E<> p}, {@code A[] p}, {@code A<> p}, {@code E[] p} or {@code p --> q}.
 *
 * @param pos     where it was written
 * @param kind    the path quantifier
 * @param formula the state formula ({@code p})
 * @param target  {@code q} of a leads-to query, else null
 * @param comment the query's comment, or null
 */
public record Query(Pos pos, Kind kind, Expr formula, Expr target, String comment) {

    /** The kinds of query. */
    public enum Kind { EXISTS_EVENTUALLY, ALWAYS_GLOBALLY, ALWAYS_EVENTUALLY, EXISTS_GLOBALLY, LEADS_TO }
}
