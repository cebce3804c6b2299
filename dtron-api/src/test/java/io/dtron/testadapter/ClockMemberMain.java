package io.dtron.testadapter;

import io.dtron.api.internal.TestHooks;
import io.dtron.api.Dtron;
import io.dtron.api.DtronListener;
import io.dtron.api.DtronOptions;
import io.dtron.testsupport.FreePorts;
import io.dtron.api.IDtronChannel;
import io.dtron.api.IDtronChannelValued;
import io.dtron.testsupport.Waits;
import java.time.Duration;
import java.util.Map;
import java.util.concurrent.CountDownLatch;
import java.util.concurrent.TimeUnit;

/**
 * A member with a shifted clock, using only {@code io.dtron.api}: once it has an estimate of its clock's offset to
 * the tester it publishes {@code estimated(offset_us, error_us)} (the message also carries the estimate in its
 * clock fields). {@code slow(millis)} keeps its listener thread busy that long. When a run starts it schedules, at
 * run time 10 units, {@code fired()} with the firing time as event time. Leaves on {@code quit}. Arguments: cluster
 * name, member name, clock shift in milliseconds. Exit code 0 after {@code quit}, 2 if there was no quit within a
 * minute, 1 if there was no estimate within {@link Waits#TIMEOUT}.
 */
public final class ClockMemberMain {
    /** {@code estimated(offset_us, error_us)}. */
    public static final IDtronChannel ESTIMATED = IDtronChannel.of("estimated", "offset_us", "error_us");
    /** {@code slow(millis)}. */
    public static final IDtronChannel SLOW = IDtronChannel.of("slow", "millis");
    /** {@code fired()}. */
    public static final IDtronChannel FIRED = IDtronChannel.of("fired");
    /** {@code quit()}. */
    public static final IDtronChannel QUIT = IDtronChannel.of("quit");
    /** The run time at which {@code fired} is scheduled, in time units. */
    public static final double FIRE_AT_UNITS = 10;

    private ClockMemberMain() {
    }

    public static void main(String[] args) throws InterruptedException {
        CountDownLatch quitting = new CountDownLatch(1);
        DtronOptions options = FreePorts.onPort(TestHooks.clockShift(DtronOptions.builder().clusterName(args[0])
                .memberName(args[1]), Duration.ofMillis(Long.parseLong(args[2]))), args, 3).build();
        try (Dtron dtron = Dtron.connect(options)) {
            addListeners(dtron, quitting);
            Waits.await("a clock offset estimate").until(dtron::hasClockOffset);
            System.out.println("offset " + dtron.getClockOffsetNanos() + " error " + dtron.getClockErrorNanos());
            System.out.flush();
            dtron.send(ESTIMATED.constructValued(Map.of("offset_us", (int) (dtron.getClockOffsetNanos() / 1000),
                    "error_us", (int) (dtron.getClockErrorNanos() / 1000))));
            if (!quitting.await(1, TimeUnit.MINUTES)) {
                System.exit(2);
            }
        }
    }

    /** Adds the listeners for {@code slow}, {@code quit} and the start of a run. */
    public static void addListeners(Dtron dtron, CountDownLatch quitting) {
        dtron.addDtronListener(new DtronListener(SLOW) {
            @Override
            public void messageReceived(IDtronChannelValued message) {
                try {
                    Thread.sleep(message.getVariables().get("millis"));
                } catch (InterruptedException e) {
                    Thread.currentThread().interrupt();
                }
            }
        });
        dtron.addDtronListener(new DtronListener(QUIT) {
            @Override
            public void messageReceived(IDtronChannelValued message) {
                quitting.countDown();
            }
        });
        dtron.addDtronListener(new DtronListener(Dtron.RUN_START) {
            @Override
            public void messageReceived(IDtronChannelValued message) {
                dtron.runClock().scheduleAt(FIRE_AT_UNITS,
                        () -> dtron.send(FIRED.constructValued(Map.of()), dtron.currentTimeNanos()));
            }
        });
    }
}
