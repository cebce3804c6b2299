package io.dtron.testsupport;

import java.util.concurrent.Executor;

/**
 * An executor that runs each task on a daemon thread of its own. A test's simulated peer (an adapter's script) runs
 * there, not in the common pool, which has a single thread on two cores: there the script could wait behind another
 * test's task until the tester's timeouts had passed.
 */
public final class OwnThreads {
    private OwnThreads() {
    }

    /** An executor that starts a new daemon thread, named {@code name}, for every task. */
    public static Executor named(String name) {
        return task -> {
            Thread thread = new Thread(task, name);
            thread.setDaemon(true);
            thread.start();
        };
    }
}
