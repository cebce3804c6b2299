package io.dtron.engine.coverage;

/**
 * The test purposes of a run (its {@code --goal} queries, numbered from 1), as a {@link StopCondition}'s
 * {@code reached(N)} asks about them. Whoever tracks the goals implements it; it is asked on the tester's thread,
 * after every event, and must answer at once.
 */
public interface Goals {
    /** No goals. */
    Goals NONE = new Goals() {
        @Override
        public int count() {
            return 0;
        }

        @Override
        public boolean reached(int goal) {
            return false;
        }
    };

    /** How many goals the run has. */
    int count();

    /** Whether goal number {@code goal} (1 to {@link #count()}) has been reached so far in this run. */
    boolean reached(int goal);

    /** How goal number {@code goal} reads, for the verdict line: its query by default. */
    default String describe(int goal) {
        return "goal " + goal;
    }
}
