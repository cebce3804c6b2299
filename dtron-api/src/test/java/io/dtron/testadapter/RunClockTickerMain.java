package io.dtron.testadapter;

import io.dtron.api.internal.TestHooks;
import io.dtron.api.Dtron;
import io.dtron.api.DtronOptions;
import io.dtron.testsupport.FreePorts;
import io.dtron.testsupport.Waits;
import java.time.Duration;
import java.util.concurrent.CountDownLatch;
import java.util.concurrent.TimeUnit;

/**
 * A {@link RunClockTicker} process, using only {@code io.dtron.api}, whose clock may be off. Arguments: cluster
 * name, member name, variant ({@code correct} or {@code slow}), clock shift in milliseconds (as if this host's
 * clock were off by that much), the number of testers to serve. Prints {@code joined} once on the bus, {@code
 * offset} once it has an estimate of a tester's clock, and leaves when that many other members have left. Exit code 0, or 2 if they did not come and go within ten minutes.
 */
public final class RunClockTickerMain {
    private RunClockTickerMain() {
    }

    public static void main(String[] args) throws InterruptedException {
        DtronOptions options = FreePorts.onPort(TestHooks.clockShift(DtronOptions.builder().clusterName(args[0])
                .memberName(args[1]), Duration.ofMillis(Long.parseLong(args[3]))), args, 5).build();
        CountDownLatch testersGone = new CountDownLatch(Integer.parseInt(args[4]));
        boolean done;
        try (Dtron dtron = Dtron.connect(options); RunClockTicker ticker = new RunClockTicker(args[2])) {
            dtron.addMembershipListener((members, joined, left) -> left.forEach(member -> testersGone.countDown()));
            ticker.start(dtron);
            System.out.println("joined " + dtron.getMembers());
            System.out.flush();
            Thread announcer = new Thread(() -> {
                Waits.await("a clock offset estimate").atMost(Duration.ofMinutes(10)).until(dtron::hasClockOffset);
                System.out.println("offset " + dtron.getClockOffset().orElseThrow());
                System.out.flush();
            }, "offset-announcer");
            announcer.setDaemon(true);
            announcer.start();
            done = testersGone.await(10, TimeUnit.MINUTES);
        }
        System.exit(done ? 0 : 2);
    }
}
