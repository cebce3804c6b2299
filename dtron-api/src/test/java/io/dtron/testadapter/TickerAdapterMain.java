package io.dtron.testadapter;

import io.dtron.api.Dtron;
import io.dtron.api.DtronListener;
import io.dtron.api.DtronOptions;
import io.dtron.api.IDtronChannelValued;
import java.util.Set;
import java.util.concurrent.ConcurrentHashMap;
import java.util.concurrent.CountDownLatch;
import java.util.concurrent.TimeUnit;

/**
 * A ticker adapter process, using only {@code io.dtron.api}: a {@link BusTicker} on the bus. Arguments: cluster
 * name, member name, variant ({@code correct} or {@code slow}), the number of runs to serve, and optionally the NATS
 * server URLs (comma-separated) of a NATS bus and the bus's secret (a test's, so on the command line; {@code insecure}
 * for none). Prints
 * {@code joined} once on the bus; stops ticking whenever a tester that started a run here leaves, leaves when that
 * many have left the bus, and prints {@code resets N}; other members (observers, refused testers) come and go
 * unnoticed. Exit code 0, or 2 if they did not come and go within ten minutes.
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
        if (args.length > 5 && args[5].equals("insecure")) {
            options.insecure(true);
        } else if (args.length > 5) {
            options.secret(args[5]);
        }
        try (Dtron dtron = Dtron.connect(options.build());
                ticker) {
            // the listeners' thread hears a tester's run start before the news that it left
            Set<String> runTesters = ConcurrentHashMap.newKeySet();
            dtron.addDtronListener(new DtronListener(Dtron.RUN_START) {
                @Override
                public void messageReceived(IDtronChannelValued start) {
                    runTesters.add(start.getSender());
                }
            });
            dtron.addMembershipListener((members, joined, left) -> left.stream().filter(runTesters::remove)
                    .forEach(member -> {
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
