package io.dtron.cli;

import io.dtron.api.Dtron;
import io.dtron.api.DtronListener;
import io.dtron.api.DtronOptions;
import io.dtron.api.IDtronChannel;
import io.dtron.api.IDtronChannelValued;
import io.dtron.testsupport.FreePorts;
import io.dtron.testsupport.Waits;
import java.util.Map;
import java.util.concurrent.TimeUnit;

/**
 * The system of {@code crossing.xta} behind a bus adapter in a JVM of its own. Arguments: the cluster name, the variant
 * and, optionally, the bus's first port. {@code crossing}: when input y reaches it, the system has just produced x,
 * which the adapter publishes with the time it happened, 5 ms later (held up between stamping and sending), before it
 * applies y (its listener returns, and the automatic acknowledgement says y was applied then): on the bus, x crosses y,
 * but it happened before. {@code late}: y is applied at once, and x happens 5 ms after it: a fault of the system.
 * Prints "ready" once it knows the tester's clock; runs until it is stopped.
 */
public final class CrossingAdapterMain {
    private static final IDtronChannel X = IDtronChannel.of("x");
    private static final IDtronChannel Y = IDtronChannel.of("y");

    private CrossingAdapterMain() {
    }

    public static void main(String[] args) throws InterruptedException {
        boolean crossing = args[1].equals("crossing");
        try (Dtron dtron = Dtron.connect(FreePorts.onPort(DtronOptions.builder().clusterName(args[0])
                .memberName("crossing-" + args[1]), args, 2).build())) {
            dtron.declareOutputs(X);
            dtron.addDtronListener(new DtronListener(Y) {
                @Override
                public void messageReceived(IDtronChannelValued message) {
                    Dtron bus = getDtron();
                    if (crossing) {
                        long happened = bus.currentTimeNanos();
                        sleep(5);
                        bus.send(X.constructValued(Map.of()), happened);
                        sleep(1);
                    } else {
                        Thread late = new Thread(() -> {
                            sleep(5);
                            bus.send(X.constructValued(Map.of()));
                        });
                        late.start();
                    }
                }
            });
            Waits.await("a clock offset estimate").until(dtron::hasClockOffset);
            System.out.println("ready");
            System.out.flush();
            Thread.sleep(TimeUnit.MINUTES.toMillis(5)); // until the test stops this JVM
        }
    }

    private static void sleep(long millis) {
        try {
            Thread.sleep(millis);
        } catch (InterruptedException e) {
            Thread.currentThread().interrupt();
        }
    }
}
