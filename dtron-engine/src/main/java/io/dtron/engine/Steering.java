package io.dtron.engine;

import java.util.List;
import java.util.Objects;

/**
 * Test purposes and how the tester steers toward them: given to {@link OnlineTester#steer}.
 *
 * @param strategy  how inputs and delays are chosen
 * @param goals     test purposes, each an {@code E<> p} query in Uppaal's syntax; once every goal is reached or
 *                  can no longer be, the run ends: INCONCLUSIVE when one can no longer be reached, PASSED when all
 *                  were reached and {@code stopWhenDone}; with {@code stopWhenDone}, a goal still open at the timeout
 *                  ends the run INCONCLUSIVE too
 * @param horizon   how many moves ahead the strategy looks: a target farther than that does not steer the choice
 * @param fairness  K of thesis 3.4.2: a choice of the system whose alternatives were taken a number of times that
 *                  differ by more than K, while a goal (or, for {@link Strategy#COVERAGE}, an uncovered edge) needs
 *                  the starved one, ends the run INCONCLUSIVE; -1 for no such check
 * @param stopWhenDone whether the run ends PASSED once every goal is reached (false: it runs on until its other
 *                  stop conditions, a stop condition's {@code reached(N)} asking {@link OnlineTester#goalReached})
 */
public record Steering(Strategy strategy, List<String> goals, int horizon, int fairness, boolean stopWhenDone) {
    /**
     * The horizon when none is given: 100 moves (a move of the closed network, internal ones included: on LightContr,
     * the environment's last edge is 38 moves from the start).
     */
    public static final int DEFAULT_HORIZON = 100;

    public Steering {
        Objects.requireNonNull(strategy, "strategy");
        goals = List.copyOf(goals);
        if (horizon < 1) {
            throw new IllegalArgumentException("the horizon must be at least 1 move, not " + horizon);
        }
        if (fairness < -1) {
            throw new IllegalArgumentException("the fairness bound must be 0 or more, not " + fairness);
        }
    }

    /** {@code strategy} toward {@code goals}, with the default horizon, no fairness check, stopping when done. */
    public static Steering of(Strategy strategy, List<String> goals) {
        return new Steering(strategy, goals, DEFAULT_HORIZON, -1, true);
    }
}
