package io.dtron.junit;

import io.dtron.api.Dtron;
import io.dtron.api.DtronOptions;
import java.net.InetAddress;
import java.util.concurrent.CountDownLatch;

/**
 * The correct lamp behind its bus adapter in a JVM of its own: joins the bus named by its argument on loopback, says
 * so, and serves until it is killed.
 */
public final class LampProcess {
    private LampProcess() {
    }

    public static void main(String[] args) throws InterruptedException {
        Dtron dtron = Dtron.connect(DtronOptions.builder().clusterName(args[0])
                .bindAddress(InetAddress.getLoopbackAddress()).build());
        new LampBusAdapter(1.5).start(dtron);
        System.out.println("lamp joined bus " + args[0] + " as " + dtron.getMemberId());
        new CountDownLatch(1).await();
    }
}
