package io.dtron.engine.verify;

/**
 * A query that cannot be checked as written: a syntax error, an unknown name, a type error. The message names
 * the query and the column of the problem.
 */
public final class QueryException extends RuntimeException {
    private static final long serialVersionUID = 1L;

    /** An error in a query, with a message that names it. */
    public QueryException(String message) {
        super(message);
    }
}
