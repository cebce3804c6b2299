package io.dtron.cli;

import io.dtron.api.Dtron;
import io.dtron.api.DtronListener;
import io.dtron.api.DtronOptions;
import io.dtron.api.IDtronChannel;
import io.dtron.api.IDtronChannelValued;
import io.dtron.api.RunClock;
import java.util.Map;
import java.util.concurrent.TimeUnit;
import org.slf4j.Logger;
import org.slf4j.LoggerFactory;

/**
 * The system of {@code racing.xta} behind a bus adapter in a JVM of its own, on the run's clock. Arguments: the
 * cluster name and the variant. {@code correct}: done 2 units after start is applied (the model allows 1 to 5), and
 * timeout 11.5 units after time 0 or its last output when no start came (so it races a start that comes after the
 * environment's window of 9 to 11 units closed). {@code late}: done 8 units after start, 3 units after the model's
 * deadline: a fault of the system. Logs a warning when an output of the correct system went out after the model's
 * deadline by its own run clock (its JVM was held up), so that a FAILED verdict can be told from a wrong one. Prints
 * "joined" once on the bus; runs until it is stopped.
 */
public final class RacingAdapterMain {
    private static final IDtronChannel START = IDtronChannel.of("start");
    private static final IDtronChannel DONE = IDtronChannel.of("done");
    private static final IDtronChannel TIMEOUT = IDtronChannel.of("timeout");
    private static final double TIMEOUT_UNITS = 11.5;
    /** The model's deadline of done after start, and of timeout after the last output, in time units. */
    private static final double DONE_DEADLINE = 5;
    private static final double TIMEOUT_DEADLINE = 12;
    private static final Logger LOG = LoggerFactory.getLogger(RacingAdapterMain.class);

    private final Dtron dtron;
    private final double doneUnits;
    /** Guarded by {@code this}: the next output, and its generation (an output task of an earlier one does nothing). */
    private RunClock.Task pending;
    private long generation;
    /** Guarded by {@code this}: an output is being sent, and a start that came meanwhile, applied after it. */
    private boolean sending;
    private IDtronChannelValued deferredStart;

    private RacingAdapterMain(Dtron dtron, double doneUnits) {
        this.dtron = dtron;
        this.doneUnits = doneUnits;
    }

    public static void main(String[] args) throws InterruptedException {
        double done = switch (args[1]) {
            case "correct" -> 2;
            case "late" -> 8;
            default -> throw new IllegalArgumentException("unknown variant '" + args[1] + "' (correct, late)");
        };
        try (Dtron dtron = Dtron.connect(DtronOptions.builder().clusterName(args[0]).memberName("racing-" + args[1])
                .build())) {
            RacingAdapterMain system = new RacingAdapterMain(dtron, done);
            dtron.declareOutputs(DONE, TIMEOUT);
            dtron.addDtronListener(new DtronListener(Dtron.RUN_START) {
                @Override
                public void messageReceived(IDtronChannelValued message) {
                    system.runStarted();
                }

                @Override
                protected boolean onReceivingThread() {
                    return true;
                }
            });
            // start is applied on the thread that received it (no hand-off to the listeners' thread), and this
            // listener waits for nothing there: the adapter's lock is never held while an output is sent
            dtron.addDtronListener(new DtronListener(START) {
                @Override
                public void messageReceived(IDtronChannelValued message) {
                    system.started(message);
                }

                @Override
                protected boolean autoAcknowledge() {
                    return false;
                }

                @Override
                protected boolean onReceivingThread() {
                    return true;
                }
            });
            system.warmUp();
            System.out.println("joined");
            System.out.flush();
            Thread.sleep(TimeUnit.MINUTES.toMillis(30)); // until it is stopped
        }
    }

    /**
     * Runs this adapter's own code once before any run (its tasks made and cancelled, its output path's classes
     * loaded), so that the first start of a run does not pay for it: at 1 ms per unit a first call took 2 to 3 ms.
     */
    private void warmUp() {
        dtron.runClock().scheduleAt(0, outputTask(TIMEOUT, 0, -1)).cancel();
        dtron.runClock().scheduleAt(0, outputTask(DONE, 0, -1)).cancel();
        String.format("%.3f", 0.0);
    }

    /**
     * The task that sends {@code channel}, which the model requires by run time {@code deadlineUnits}, unless the
     * adapter scheduled something else since (its generation {@code generation} is over).
     */
    private Runnable outputTask(IDtronChannel channel, double deadlineUnits, long generation) {
        return () -> output(channel, deadlineUnits, generation);
    }

    /** The run starts: the system waits from time 0. */
    private synchronized void runStarted() {
        waitFrom(0);
    }

    /** Waiting from run time {@code fromUnits}: times out 11.5 units later unless start comes. */
    private void waitFrom(double fromUnits) {
        schedule(fromUnits + TIMEOUT_UNITS, TIMEOUT, fromUnits + TIMEOUT_DEADLINE);
    }

    /**
     * Start is applied now, and acknowledged with that time; while an output is being sent it is applied right after
     * the output went out (by the output's thread), so that the input follows the output as the system saw them.
     */
    private void started(IDtronChannelValued message) {
        long appliedAt;
        synchronized (this) {
            if (sending) {
                deferredStart = message;
                return;
            }
            appliedAt = apply();
        }
        dtron.acknowledge(message, appliedAt);
    }

    /**
     * Applies start under the lock: done is due in 2 (or 8) units; returns when, on this member's clock. That time is
     * read before the run time that done counts from, so that a thread held up between the two makes done later
     * than 2 units after the acknowledged time, never earlier.
     */
    private long apply() {
        long appliedAt = dtron.currentTimeNanos();
        RunClock clock = dtron.runClock();
        if (clock.isRunning()) {
            double now = clock.nowUnits();
            schedule(now + doneUnits, DONE, doneUnits < DONE_DEADLINE ? now + DONE_DEADLINE : Double.MAX_VALUE);
        }
        return appliedAt;
    }

    /**
     * Sends an output that the model requires by run time {@code deadlineUnits}, warning when it is past, and waits
     * for start again. The lock is not held while the output is sent: a start listener on the bus's receiving thread
     * may not wait for a thread that sends (see DtronListener.onReceivingThread).
     */
    private void output(IDtronChannel channel, double deadlineUnits, long generation) {
        double now;
        long happened;
        synchronized (this) {
            if (generation != this.generation) {
                return; // start came before this output went out: done is due instead
            }
            sending = true;
            // the output's time, read before the run time the next timeout counts from (as in apply)
            happened = dtron.currentTimeNanos();
            now = dtron.runClock().nowUnits();
        }
        IDtronChannelValued start;
        long appliedAt = 0;
        try {
            dtron.send(channel.constructValued(Map.of()), happened);
        } finally {
            synchronized (this) {
                sending = false;
                start = deferredStart;
                deferredStart = null;
                if (start != null) {
                    appliedAt = apply();
                } else {
                    waitFrom(now);
                }
            }
        }
        if (start != null) {
            dtron.acknowledge(start, appliedAt);
        }
        if (now > deadlineUnits) {
            LOG.warn("{} at t={} by this adapter's run clock, after its deadline t={} (this JVM was held up)",
                    channel.getChannelName(), String.format("%.3f", now), String.format("%.3f", deadlineUnits));
        }
    }

    /** Schedules the next output, replacing the pending one; called under the lock. */
    private void schedule(double atUnits, IDtronChannel channel, double deadlineUnits) {
        if (pending != null) {
            pending.cancel();
        }
        generation++;
        pending = dtron.runClock().scheduleAt(atUnits, outputTask(channel, deadlineUnits, generation));
    }
}
