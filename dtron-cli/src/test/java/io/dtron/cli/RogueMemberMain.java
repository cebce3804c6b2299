package io.dtron.cli;

import io.dtron.api.Dtron;
import io.dtron.api.DtronOptions;
import io.dtron.api.internal.BusConnector;
import io.dtron.api.internal.proto.Sync;
import io.dtron.api.internal.proto.Variable;
import io.dtron.bus.internal.Transport;
import io.dtron.bus.internal.JGroupsTransport;
import java.util.concurrent.CountDownLatch;
import java.util.concurrent.TimeUnit;

/**
 * A bus member that sends what no adapter should: once a run has started, one message that is no Sync, one on an
 * unknown channel, one with an unknown variable and one with a missing variable, then prints {@code sent 4} and
 * stays on the bus until it is killed (five minutes at most). Argument: the cluster name.
 */
public final class RogueMemberMain {
    private RogueMemberMain() {
    }

    public static void main(String[] args) throws Exception {
        CountDownLatch started = new CountDownLatch(1);
        DtronOptions options = DtronOptions.builder().clusterName(args[0]).build();
        try (Transport rogue = JGroupsTransport.connect(BusConnector.settings(options, "rogue"))) {
            rogue.subscribe(Dtron.RUN_START.getChannelName(), message -> started.countDown());
            System.out.println("joined");
            System.out.flush();
            if (!started.await(5, TimeUnit.MINUTES)) {
                System.exit(2);
            }
            Thread.sleep(300);
            rogue.publish("tick", new byte[] {(byte) 0xFF, (byte) 0xFF, 0x07});
            rogue.publish("bogus", sync("bogus"));
            rogue.publish("tick", sync("tick", variable("seq", 1), variable("colour", 2)));
            rogue.publish("tick", sync("tick"));
            System.out.println("sent 4");
            System.out.flush();
            Thread.sleep(TimeUnit.MINUTES.toMillis(5));
        }
    }

    private static Variable variable(String name, int value) {
        return Variable.newBuilder().setName(name).setValue(value).build();
    }

    private static byte[] sync(String name, Variable... variables) {
        Sync.Builder sync = Sync.newBuilder().setName(name);
        for (Variable variable : variables) {
            sync.addVariables(variable);
        }
        return sync.build().toByteArray();
    }
}
