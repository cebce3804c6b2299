package io.dtron.testadapter;

import io.dtron.api.Dtron;
import io.dtron.api.DtronOptions;
import java.util.concurrent.CountDownLatch;
import java.util.concurrent.TimeUnit;

/**
 * A ticker adapter process, using only {@code io.dtron.api}: a {@link BusTicker} on the bus. Arguments: cluster
 * name, member name, variant ({@code correct} or {@code slow}), the number of runs to serve, and optionally the NATS
 * server URLs (comma-separated) of a NATS bus and the bus's secret (a test's, so on the command line). Prints
 * {@code joined} once on the bus; stops ticking whenever another member (a tester) leaves, leaves when that many
 * have left the bus, and prints {@code resets N}. Exit code 0, or 2 if they did not come and go within ten minutes.
 */
public final class TickerAdapterMain {
    private TickerAdapterMain() {
    }

    public static void main(String[] args) throws InterruptedException {
        String cluster = args[0];
        String name = args[1];
        String variant = args[2];
        CountDownLatch testersGone = new CountDownLatch(Integer.parseInt(args[3]));
        boolean done;
        BusTicker ticker = new BusTicker(variant);
        DtronOptions.Builder options = DtronOptions.builder().clusterName(cluster).memberName(name);
        if (args.length > 4) {
            options.natsServers(java.util.List.of(args[4].split(",")));
        }
        if (args.length > 5) {
            options.secret(args[5]);
        }
        try (Dtron dtron = Dtron.connect(options.build());
                ticker) {
            dtron.addMembershipListener((members, joined, left) -> left.forEach(member -> {
                ticker.stop();
                testersGone.countDown();
            }));
            ticker.start(dtron);
            System.out.println("joined " + dtron.getMembers());
            System.out.flush();
            done = testersGone.await(10, TimeUnit.MINUTES);
            System.out.println("resets " + ticker.resets());
        }
        System.exit(done ? 0 : 2);
    }
}
