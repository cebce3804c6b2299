package io.dtron.xta.ast;

import io.dtron.xta.Diagnostic;
import io.dtron.xta.Pos;
import java.util.List;

/**
 * A query of Uppaal's verifier as written: symbolic ({@code E<> p}, {@code A[] p}, {@code A<> p},
 * {@code E[] p}, {@code p --> q}, {@code sup: e}), statistical ({@code Pr[<=10](<> p)}, {@code E[<=10](max: e)},
 * {@code simulate [<=10] {e}}), strategies ({@code strategy S = control: A[] p}, {@code ... under S}) or
 * scenarios ({@code sat: S}). A query that does not parse is kept with kind {@link Kind#INVALID} and its
 * errors; it never stops the model from loading.
 *
 * @param pos      where it was written
 * @param kind     what the query asks
 * @param text     the query's text, trimmed
 * @param formula  the state formula {@code p} of the five symbolic kinds, else null
 * @param target   {@code q} of a leads-to query, else null
 * @param strategy the strategy named after {@code under}, or null
 * @param comment  the query's comment, or null
 * @param errors   the query's syntax errors, empty when it parsed
 */
public record Query(Pos pos, Kind kind, String text, Expr formula, Expr target, String strategy, String comment,
                    List<Diagnostic> errors) {
    public Query {
        errors = List.copyOf(errors);
    }

    /** What a query asks. */
    public enum Kind {
        /** {@code E<> p} */
        EXISTS_EVENTUALLY,
        /** {@code A[] p} */
        ALWAYS_GLOBALLY,
        /** {@code A<> p} */
        ALWAYS_EVENTUALLY,
        /** {@code E[] p} */
        EXISTS_GLOBALLY,
        /** {@code p --> q} */
        LEADS_TO,
        /** {@code sup: e}, {@code inf: e}, {@code bounds: e}, optionally with a condition in braces */
        VALUE_BOUNDS,
        /** {@code control: A[] p} and timed control */
        CONTROL,
        /** {@code strategy S = ...} */
        STRATEGY,
        /** {@code saveStrategy(...)}, {@code loadStrategy(...)} */
        STRATEGY_FILE,
        /** {@code sat: S}, a live sequence chart scenario */
        SCENARIO,
        /** {@code simulate [<=10] {e}} */
        SIMULATE,
        /** {@code Pr[<=10](<> p)}, possibly compared with a number or another probability */
        PROBABILITY,
        /** {@code E[<=10](max: e)} */
        EXPECTATION,
        /** {@code minE(e) [<=10]: <> p} and {@code maxE}: learning a strategy */
        OPTIMISE,
        /** A query that does not parse; see {@link #errors()} */
        INVALID
    }

    /** Whether the query parsed. */
    public boolean isValid() {
        return errors.isEmpty();
    }
}
