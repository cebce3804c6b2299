package io.dtron.testadapter;

import io.dtron.api.Dtron;
import io.dtron.api.DtronListener;
import io.dtron.api.DtronOptions;
import io.dtron.testsupport.FreePorts;
import io.dtron.api.IDtronChannel;
import io.dtron.api.IDtronChannelValued;
import java.time.Duration;
import java.util.Map;
import java.util.concurrent.CountDownLatch;
import java.util.concurrent.TimeUnit;

/**
 * A small adapter that uses only {@code io.dtron.api}: answers every
 * {@code move(amount)} with {@code done(2 * amount)}, announces itself with
 * {@code ready} and leaves on {@code quit}. Arguments: the cluster name and, optionally, the bus's first port (its
 * port range {@value io.dtron.testsupport.FreePorts#BUS_RANGE}).
 * Exit code 0 after {@code quit}, 2 if none came within a minute.
 */
public final class EchoAdapterMain {
    private EchoAdapterMain() {
    }

    public static void main(String[] args) throws InterruptedException {
        IDtronChannel move = IDtronChannel.of("move", "amount");
        IDtronChannel done = IDtronChannel.of("done", "amount");
        IDtronChannel ready = IDtronChannel.of("ready");
        IDtronChannel quit = IDtronChannel.of("quit");
        CountDownLatch quitting = new CountDownLatch(1);
        try (Dtron dtron = Dtron.connect(FreePorts.onPort(DtronOptions.builder().clusterName(args[0])
                .memberName("echo-adapter"), args, 1).build())) {
            dtron.addDtronListener(new DtronListener(move) {
                @Override
                public void messageReceived(IDtronChannelValued message) {
                    int amount = message.getVariables().get("amount");
                    getDtron().send(done.constructValued(Map.of("amount", 2 * amount)));
                }
            });
            dtron.addDtronListener(new DtronListener(quit) {
                @Override
                public void messageReceived(IDtronChannelValued message) {
                    quitting.countDown();
                }
            });
            if (!dtron.awaitMembers(2, Duration.ofSeconds(30))) {
                System.exit(2);
            }
            dtron.send(ready.constructValued(Map.of()));
            if (!quitting.await(60, TimeUnit.SECONDS)) {
                System.exit(2);
            }
        }
    }
}
