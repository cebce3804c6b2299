package io.dtron.testadapter;

import io.dtron.api.Dtron;
import io.dtron.api.DtronListener;
import io.dtron.api.DtronOptions;
import io.dtron.api.IDtronChannel;
import io.dtron.api.IDtronChannelValued;
import java.io.IOException;
import java.nio.file.Files;
import java.nio.file.Path;
import java.time.Duration;
import java.util.ArrayList;
import java.util.List;
import java.util.Map;
import java.util.Set;
import java.util.concurrent.ConcurrentHashMap;
import java.util.concurrent.CountDownLatch;
import java.util.concurrent.TimeUnit;

/**
 * One member of the total-order test, using only {@code io.dtron.api}.
 * Arguments: cluster name, member name, output file, messages to publish,
 * number of members, and optionally the NATS server URLs (comma-separated) of a NATS bus. Waits until it heard every member announce itself
 * (answering each newcomer's announcement with its own), publishes
 * {@code order(n)} for n = 1..messages, records "sender n sequence" of every
 * {@code order} message it receives, in receive order, to the output file,
 * and leaves once every member has finished. Exit code 0 if it received all
 * messages of all members, 2 if the members did not meet, 3 if messages or
 * members went missing.
 */
public final class OrderMemberMain {
    private OrderMemberMain() {
    }

    public static void main(String[] args) throws InterruptedException, IOException {
        String cluster = args[0];
        String name = args[1];
        Path out = Path.of(args[2]);
        int messages = Integer.parseInt(args[3]);
        int members = Integer.parseInt(args[4]);
        DtronOptions.Builder options = DtronOptions.builder().clusterName(cluster).memberName(name);
        if (args.length > 5) {
            options.natsServers(List.of(args[5].split(",")));
        }

        IDtronChannel order = IDtronChannel.of("order", "n");
        IDtronChannel ready = IDtronChannel.of("ready");
        IDtronChannel finished = IDtronChannel.of("finished");
        List<String> received = new ArrayList<>(messages * members);
        CountDownLatch allReceived = new CountDownLatch(messages * members);
        Set<String> readyMembers = ConcurrentHashMap.newKeySet();
        CountDownLatch allReady = new CountDownLatch(members);
        Set<String> finishedMembers = ConcurrentHashMap.newKeySet();
        CountDownLatch allFinished = new CountDownLatch(members);

        try (Dtron dtron = Dtron.connect(options.build())) {
            dtron.addDtronListener(new DtronListener(order) {
                @Override
                public void messageReceived(IDtronChannelValued message) {
                    received.add(message.getSender() + " " + message.getVariables().get("n") + " "
                            + message.getSequence());
                    allReceived.countDown();
                }
            });
            dtron.addDtronListener(new DtronListener(ready) {
                @Override
                public void messageReceived(IDtronChannelValued message) {
                    if (readyMembers.add(message.getSender())) {
                        allReady.countDown();
                        if (!message.getSender().equals(name)) {
                            // answer a newcomer, which may have missed this member's announcement
                            getDtron().send(ready.constructValued(Map.of()));
                        }
                    }
                }
            });
            dtron.addDtronListener(new DtronListener(finished) {
                @Override
                public void messageReceived(IDtronChannelValued message) {
                    if (finishedMembers.add(message.getSender())) {
                        allFinished.countDown();
                    }
                }
            });
            if (!dtron.awaitMembers(members, Duration.ofSeconds(60))) {
                System.err.println(name + ": members " + dtron.getMembers());
                System.exit(2);
            }
            dtron.send(ready.constructValued(Map.of()));
            if (!allReady.await(60, TimeUnit.SECONDS)) {
                System.err.println(name + ": heard only " + readyMembers);
                System.exit(2);
            }

            for (int n = 1; n <= messages; n++) {
                dtron.send(order.constructValued(Map.of("n", n)));
            }
            boolean complete = allReceived.await(90, TimeUnit.SECONDS);
            synchronized (received) {
                Files.write(out, received);
            }
            dtron.send(finished.constructValued(Map.of()));
            // the others may take long to catch up (a member that lost its server and reconnected, on a loaded
            // machine): wait for them as long as the tests wait for the slowest member (150 s)
            boolean allDone = allFinished.await(150, TimeUnit.SECONDS);
            if (!complete || !allDone) {
                System.err.println(name + ": received " + received.size() + ", finished " + finishedMembers);
                System.exit(3);
            }
        }
    }
}
