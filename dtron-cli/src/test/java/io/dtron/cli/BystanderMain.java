package io.dtron.cli;

import io.dtron.api.Dtron;
import io.dtron.api.DtronListener;
import io.dtron.api.DtronOptions;
import io.dtron.api.IDtronChannel;
import io.dtron.api.IDtronChannelValued;
import java.util.concurrent.TimeUnit;

/**
 * A bus member that serves no channel of the ticker model: it listens to {@code weather}, a channel of no model, and
 * watches the ticker's {@code tick} (an observer: it receives an output, it applies no input), prints {@code joined}
 * and stays on the bus until it is killed (five minutes at most). Arguments: the cluster name and the member name.
 */
public final class BystanderMain {
    private BystanderMain() {
    }

    public static void main(String[] args) throws InterruptedException {
        try (Dtron dtron = Dtron.connect(DtronOptions.builder().clusterName(args[0]).memberName(args[1]).build())) {
            for (IDtronChannel channel : new IDtronChannel[] {IDtronChannel.of("weather"), IDtronChannel.of("tick",
                    "seq")}) {
                dtron.addDtronListener(new DtronListener(channel) {
                    @Override
                    public void messageReceived(IDtronChannelValued message) {
                    }
                });
            }
            System.out.println("joined " + dtron.getMembers());
            System.out.flush();
            Thread.sleep(TimeUnit.MINUTES.toMillis(5));
        }
    }
}
