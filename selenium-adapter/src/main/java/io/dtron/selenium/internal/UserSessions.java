package io.dtron.selenium.internal;

import io.dtron.selenium.AdapterException;
import io.dtron.selenium.WebDriverFactory;
import java.util.ArrayList;
import java.util.List;
import java.util.Map;
import java.util.Objects;
import java.util.concurrent.ConcurrentHashMap;
import java.util.concurrent.ExecutionException;
import java.util.concurrent.ExecutorService;
import java.util.concurrent.Executors;
import java.util.concurrent.Future;
import java.util.concurrent.RejectedExecutionException;
import java.util.concurrent.TimeUnit;
import org.openqa.selenium.WebDriver;
import org.openqa.selenium.WebDriverException;
import org.slf4j.Logger;
import org.slf4j.LoggerFactory;

/**
 * Not API. The simulated users: each has one worker thread, which runs that user's messages one at a time in
 * the order they came, and one browser, started on first use. Different users run in parallel.
 */
public final class UserSessions implements AutoCloseable {
    private static final Logger LOG = LoggerFactory.getLogger(UserSessions.class);
    private static final long DRAIN_SECONDS = 10;

    private final WebDriverFactory factory;
    private final String startPage;
    private final StepWatch watch;
    private final Map<Integer, User> users = new ConcurrentHashMap<>();
    private volatile boolean closed;

    /**
     * Users whose browsers come from {@code factory} and open {@code startPage} when they start.
     *
     * @param startPage the address every new browser opens before its first step (so that the browser's first
     *                  page load is done before the run), or null to leave new browsers on their blank page
     * @param watch     the watch of the users' steps; closed with the sessions
     */
    public UserSessions(WebDriverFactory factory, String startPage, StepWatch watch) {
        this.factory = Objects.requireNonNull(factory, "factory");
        this.startPage = startPage;
        this.watch = Objects.requireNonNull(watch, "watch");
    }

    /** Returns the watch of the users' steps. */
    public StepWatch watch() {
        return watch;
    }

    /** One user: a worker thread and a browser. */
    private final class User {
        private final int id;
        private final ExecutorService worker;
        private WebDriver browser;

        User(int id) {
            this.id = id;
            this.worker = Executors.newSingleThreadExecutor(r -> {
                Thread t = new Thread(r, "selenium-user-" + id);
                t.setDaemon(true);
                // a launcher such as Maven's exec:java may swallow what a thread of its own dies of
                t.setUncaughtExceptionHandler((thread, e) -> LOG.error("The thread of user {} died", id, e));
                return t;
            });
        }

        synchronized WebDriver browser() {
            if (browser == null) {
                if (closed) {
                    throw new AdapterException("the adapters are closed");
                }
                long start = System.nanoTime();
                try {
                    browser = factory.create();
                } catch (AdapterException | WebDriverException e) {
                    throw new BrowserFailure("the browser of user " + id + " did not start: " + Messages.firstLine(
                            e.getMessage()), e);
                }
                long loadStart = System.nanoTime();
                if (startPage != null) {
                    try {
                        browser.get(startPage);
                    } catch (WebDriverException e) {
                        quit();
                        throw new BrowserFailure("the browser of user " + id + " cannot open its start page "
                                + startPage + ": " + Messages.firstLine(e.getMessage()), e);
                    }
                }
                long end = System.nanoTime();
                long nanos = end - start;
                String load = startPage == null ? "" : " (" + (end - loadStart) / 1_000_000 + " ms of it loading "
                        + startPage + ")";
                StepWatch.Step step = watch.current(id);
                if (step != null) {
                    step.browserStarted(nanos);
                    LOG.warn("Started the browser of user {} in {} ms{}, within a step: that time counts against"
                            + " the system under test; start the browsers before the run (property dtron.browsers)",
                            id, nanos / 1_000_000, load);
                } else {
                    LOG.info("Started the browser of user {} in {} ms{}", id, nanos / 1_000_000, load);
                }
            }
            return browser;
        }

        synchronized void quit() {
            if (browser != null) {
                try {
                    browser.quit();
                } catch (WebDriverException e) {
                    LOG.warn("The browser of user {} did not quit cleanly: {}", id,
                            Messages.firstLine(e.getMessage()));
                }
                browser = null;
            }
        }
    }

    /**
     * Queues a task on the user's worker thread. A task that has not started when the sessions close is dropped.
     *
     * @return false if the sessions are closed and the task was dropped
     */
    public boolean submit(int user, Runnable task) {
        try {
            user(user).worker.execute(() -> {
                if (closed) {
                    LOG.info("Dropped a step of user {}: the adapters are closed", user);
                    return;
                }
                try {
                    task.run();
                } catch (Throwable e) {
                    LOG.error("A step of user {} ended with an unexpected {}", user, e.getClass().getName(), e);
                    throw e;
                }
            });
            return true;
        } catch (AdapterException | RejectedExecutionException e) {
            return false;
        }
    }

    /**
     * Returns the user's browser, starting it on first use.
     *
     * @throws AdapterException if it cannot be started, or the sessions closed before it was
     */
    public WebDriver browser(int user) {
        return user(user).browser();
    }

    /**
     * Starts the browsers of users 0 to {@code count - 1} in parallel, so that the first step of a test does not
     * wait for them.
     *
     * @throws AdapterException if a browser cannot be started
     */
    public void prestart(int count) {
        List<Future<?>> starts = new ArrayList<>();
        for (int id = 0; id < count; id++) {
            User user = user(id);
            starts.add(user.worker.submit(user::browser));
        }
        for (Future<?> start : starts) {
            try {
                start.get();
            } catch (ExecutionException e) {
                throw e.getCause() instanceof AdapterException a ? a
                        : new AdapterException("cannot start a browser: " + e.getCause(), e.getCause());
            } catch (InterruptedException e) {
                Thread.currentThread().interrupt();
                throw new AdapterException("interrupted while starting the browsers", e);
            }
        }
    }

    /** Lets the tasks under way finish (a few seconds at most), then quits every browser, in parallel. */
    @Override
    public void close() {
        close(true);
    }

    /**
     * Quits every browser, in parallel, after letting the tasks under way finish (a few seconds at most) if
     * {@code drain}, else at once: the steps under way are interrupted.
     */
    public void close(boolean drain) {
        if (closed) {
            return;
        }
        closed = true;
        watch.close();
        List<User> all = new ArrayList<>(users.values());
        all.forEach(u -> {
            if (drain) {
                u.worker.shutdown();
            } else {
                u.worker.shutdownNow();
            }
        });
        long seconds = drain ? DRAIN_SECONDS : 1;
        long deadline = System.nanoTime() + TimeUnit.SECONDS.toNanos(seconds);
        for (User user : all) {
            try {
                if (!user.worker.awaitTermination(Math.max(0, deadline - System.nanoTime()), TimeUnit.NANOSECONDS)) {
                    LOG.warn("User {} is still busy after {} s; stopping it", user.id, seconds);
                    user.worker.shutdownNow();
                }
            } catch (InterruptedException e) {
                Thread.currentThread().interrupt();
                user.worker.shutdownNow();
            }
        }
        List<Thread> quitting = new ArrayList<>();
        for (User user : all) {
            Thread t = new Thread(user::quit, "selenium-quit-" + user.id);
            t.start();
            quitting.add(t);
        }
        for (Thread t : quitting) {
            try {
                t.join();
            } catch (InterruptedException e) {
                Thread.currentThread().interrupt();
                return;
            }
        }
    }

    private User user(int id) {
        User known = users.get(id);
        if (known != null) {
            return known;
        }
        if (closed) {
            throw new AdapterException("the adapters are closed");
        }
        return users.computeIfAbsent(id, User::new);
    }
}
