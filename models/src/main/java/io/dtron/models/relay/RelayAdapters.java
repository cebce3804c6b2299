package io.dtron.models.relay;

import io.dtron.api.Dtron;
import io.dtron.api.DtronException;
import io.dtron.api.DtronListener;
import io.dtron.api.DtronOptions;
import io.dtron.api.IDtronChannel;
import io.dtron.api.IDtronChannelValued;
import io.dtron.api.RunClock;
import java.net.InetAddress;
import java.net.InetSocketAddress;
import java.net.UnknownHostException;
import java.util.ArrayList;
import java.util.List;
import java.util.Map;
import java.util.concurrent.CountDownLatch;
import org.slf4j.Logger;
import org.slf4j.LoggerFactory;

/**
 * A system with two ports and its two adapters, for distributed testing: a request at port 1 ({@code req}) is
 * answered at port 2 ({@code resp}) some time units later, on the run's clock. Each port has its own bus member, as
 * adapters on two hosts would; a tester judges each port with its own model ({@code relay/port1.xta} starts the
 * run, {@code relay/port2.xta} joins it). The {@code correct} relay answers after 4 time units, within the 2 to 9
 * that port 2's model allows; the {@code late} one after 12.
 *
 * <p>{@code java -cp dtron.jar:models.jar io.dtron.models.relay.RelayAdapters CLUSTER ADDRESS MEMBERS VARIANT [PORT
 * RANGE]}: both members bind to ADDRESS and look for the testers at MEMBERS (HOST or HOST:PORT, comma separated);
 * PORT and RANGE are the testers' {@code --port} and {@code --port-range} (default 7800 and 61). The process runs
 * until it is stopped; when it cannot join the bus, it says why in one line and exits with 1.
 */
public final class RelayAdapters {
    /** Port 1's channel: the model's {@code i_req} (port 1) and {@code o_req} (port 2). */
    public static final IDtronChannel REQ = IDtronChannel.of("req");
    /** Port 2's channel: the model's {@code o_resp}. */
    public static final IDtronChannel RESP = IDtronChannel.of("resp");

    private static final Logger LOG = LoggerFactory.getLogger(RelayAdapters.class);
    private static final String USAGE = "usage: RelayAdapters CLUSTER ADDRESS MEMBERS correct|late [PORT RANGE]";

    private RelayAdapters() {
    }

    /** Starts both ports' adapters and runs until the process is stopped. */
    public static void main(String[] args) throws InterruptedException {
        if (args.length != 4 && args.length != 6 || !List.of("correct", "late").contains(args[3])) {
            exit(USAGE);
        }
        double delayUnits = args[3].equals("correct") ? 4 : 12;
        DtronOptions.Builder options;
        try {
            int port = args.length == 6 ? Integer.parseInt(args[4]) : DtronOptions.DEFAULT_PORT;
            int range = args.length == 6 ? Integer.parseInt(args[5]) : DtronOptions.DEFAULT_PORT_RANGE;
            options = DtronOptions.builder().clusterName(args[0]).bindAddress(InetAddress.getByName(args[1]))
                    .initialMembers(members(args[2], port)).port(port).portRange(range);
            options.build();
        } catch (UnknownHostException | IllegalArgumentException | IllegalStateException e) {
            exit("RelayAdapters: " + e.getMessage() + "; " + USAGE);
            return;
        }
        try (Dtron port1 = Dtron.connect(options.memberName("relay-port1").build());
                Dtron port2 = Dtron.connect(options.memberName("relay-port2").build())) {
            port2.declareOutputs(RESP);
            port1.addDtronListener(new DtronListener(REQ) {
                @Override
                public void messageReceived(IDtronChannelValued request) {
                    // port 1's clock: it has seen the run start, which the bus ordered before this request
                    RunClock clock = getDtron().runClock();
                    if (clock.isRunning()) {
                        clock.scheduleAt(clock.nowUnits() + delayUnits, () -> respond(port2));
                    }
                }
            });
            LOG.info("Relay ({}, answers after {} time units) on bus '{}' at {}", args[3], delayUnits, args[0],
                    args[1]);
            new CountDownLatch(1).await();
        } catch (DtronException e) {
            exit("RelayAdapters: " + e.getMessage());
        }
    }

    private static void exit(String message) {
        System.err.println(message);
        System.exit(1);
    }

    private static void respond(Dtron port2) {
        port2.send(RESP.constructValued(Map.of()));
    }

    private static List<InetSocketAddress> members(String list, int defaultPort) throws UnknownHostException {
        List<InetSocketAddress> members = new ArrayList<>();
        for (String member : list.split(",")) {
            int colon = member.lastIndexOf(':');
            String host = colon < 0 ? member : member.substring(0, colon);
            int port = colon < 0 ? defaultPort : Integer.parseInt(member.substring(colon + 1));
            members.add(new InetSocketAddress(InetAddress.getByName(host), port));
        }
        return members;
    }
}
