package io.dtron.engine.verify;

import io.dtron.engine.UnsupportedModelException;
import io.dtron.engine.internal.verify.Checker;
import io.dtron.engine.internal.verify.QueryParser;
import io.dtron.engine.internal.verify.TestabilityChecker;
import io.dtron.model.Network;
import java.util.ArrayList;
import java.util.List;

/**
 * Checks queries on one network by symbolic exploration of its zone graph, with the semantics the online tester
 * runs. Not thread-safe: one verifier per thread.
 */
public final class Verifier {
    private final Network network;
    private final Checker checker;

    /**
     * A verifier of {@code network}.
     *
     * @throws UnsupportedModelException when the model uses something the engine cannot run
     */
    public Verifier(Network network, VerifierOptions options) {
        this.network = network;
        this.checker = new Checker(network, options);
    }

    /**
     * The queries written in the model ({@code <queries>} of an XML model), in order; one that does not parse
     * is {@link Query.Kind#INVALID}.
     */
    public List<Query> modelQueries() {
        List<Query> out = new ArrayList<>();
        for (io.dtron.xta.ast.Query q : network.queries()) {
            out.add(QueryParser.onLine(q.pos().text(), 0));
        }
        return out;
    }

    /**
     * Checks one query.
     *
     * @throws QueryException when it is {@link Query.Kind#INVALID} or its properties do not compile against the
     *                        model (unknown names, type errors); the message names the query, its column, and its
     *                        line when it comes from a file
     * @throws UnsupportedModelException on a model error met during the search (an index out of range, ...)
     */
    public VerificationResult verify(Query query) {
        if (query.kind() == Query.Kind.INVALID) {
            throw new QueryException(query.reason());
        }
        try {
            return checker.verify(query);
        } catch (QueryException e) {
            if (query.line() > 0) {
                throw new QueryException("line " + query.line() + ": " + e.getMessage());
            }
            throw e;
        }
    }

    /**
     * The shortest time in which a run of the model sets every one of {@code traps} (each the name of a trap, as
     * {@link io.dtron.engine.coverage.Traps#of} gives them; a trap counts once it has held), by a best-first search
     * over the zone graph with a global clock, exploring at most {@code maxStates} symbolic states.
     *
     * @throws QueryException            when a trap does not compile as a property of the model
     * @throws UnsupportedModelException on a model error met during the search
     */
    public CoverTime fastestCover(List<String> traps, long maxStates) {
        return io.dtron.engine.internal.verify.FastestCover.of(network, traps, maxStates);
    }

    /**
     * Checks that the model can serve as a test specification with {@code testInterface}: output observability
     * (the environment and the implementation interact only through inputs and outputs), then, on the
     * implementation closed by a generated canonical tester (every input offered at any time, with every value of
     * its variables, every output taken at once), input enabledness (the target's invariant included),
     * connectedness (no deadlock, every location reachable) and strong responsiveness (no reachable cycle of
     * internal moves); on the model as written, the coverage of the implementation by the model's own environment
     * and time-lock freedom; Zeno freedom by a search for cycles that take no time and structurally. See "Is the model testable?" in the site's verify page.
     *
     * @throws UnsupportedModelException on a model error met during the exploration
     */
    public TestabilityReport testability(io.dtron.model.TestInterface testInterface) {
        return new TestabilityChecker(checker).testability(testInterface);
    }
}
