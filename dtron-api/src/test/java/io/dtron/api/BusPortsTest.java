package io.dtron.api;

import static org.junit.jupiter.api.Assertions.assertEquals;
import static org.junit.jupiter.api.Assertions.assertFalse;
import static org.junit.jupiter.api.Assertions.assertNull;
import static org.junit.jupiter.api.Assertions.assertThrows;
import static org.junit.jupiter.api.Assertions.assertTrue;
import static org.junit.jupiter.api.Assumptions.assumeTrue;

import io.dtron.testsupport.FreePorts;
import io.dtron.testsupport.ListeningSockets;
import io.dtron.testsupport.ListeningSockets.Listener;
import java.io.IOException;
import java.net.InetAddress;
import java.net.ServerSocket;
import java.time.Duration;
import java.util.ArrayList;
import java.util.List;
import java.util.Set;
import java.util.concurrent.TimeUnit;
import java.util.stream.Collectors;
import org.junit.jupiter.api.AfterEach;
import org.junit.jupiter.api.Test;
import org.junit.jupiter.api.Timeout;

/**
 * Which sockets a member over TCP listens on: one only, at the bind address, on a bus port of its port range; ports
 * in use give an error naming them.
 */
@Timeout(value = 60, unit = TimeUnit.SECONDS)
class BusPortsTest {
    private static final int RANGE = 5; // bus ports P..P+5
    private final String cluster = TestClusters.uniqueName("ports");
    private final List<ServerSocket> held = new ArrayList<>();

    @AfterEach
    void release() throws IOException {
        for (ServerSocket socket : held) {
            socket.close();
        }
    }

    private DtronOptions options(InetAddress bind, int port) {
        return DtronOptions.builder().clusterName(cluster).bindAddress(bind).port(port).portRange(RANGE).build();
    }

    /** Another process's socket on the port, as another bus would hold it. */
    private void hold(InetAddress address, int port) throws IOException {
        held.add(new ServerSocket(port, 1, address));
    }

    /** This JVM's listening sockets on the ports first..first+RANGE. */
    private static Set<String> listenersIn(int first) {
        return ListeningSockets.of(ProcessHandle.current().pid()).stream()
                .filter(l -> l.port() >= first && l.port() <= first + RANGE)
                .map(Listener::toString).collect(Collectors.toSet());
    }

    @Test
    void membersListenOnlyAtTheBindAddressOnTheirBusPorts() throws Exception {
        assumeTrue(ListeningSockets.available(), "needs Linux's /proc");
        InetAddress bind = InetAddress.getByName("127.0.0.2");
        int p = FreePorts.range(RANGE, bind);
        try (Dtron a = Dtron.connect(options(bind, p)); Dtron b = Dtron.connect(options(bind, p))) {
            assertTrue(a.awaitMembers(2, Duration.ofSeconds(15)), () -> "members: " + a.getMembers());
            assertEquals(Set.of("tcp 127.0.0.2:" + p, "tcp 127.0.0.2:" + (p + 1)), listenersIn(p));
            List<Listener> wildcard = ListeningSockets.of(ProcessHandle.current().pid()).stream()
                    .filter(l -> l.address().isAnyLocalAddress()).toList();
            assertEquals(List.of(), wildcard, "no socket of this JVM listens on every interface");
        }
    }

    @Test
    void aMemberWhoseFirstBusPortIsTakenMovesToTheNext() throws Exception {
        assumeTrue(ListeningSockets.available(), "needs Linux's /proc");
        InetAddress loopback = InetAddress.getLoopbackAddress();
        int p = FreePorts.range(RANGE);
        hold(loopback, p);
        try (Dtron a = Dtron.connect(options(loopback, p))) {
            Set<String> listening = listenersIn(p);
            listening.remove("tcp 127.0.0.1:" + p); // the held one
            assertEquals(Set.of("tcp 127.0.0.1:" + (p + 1)), listening);
        }
    }

    @Test
    void portsInUseGiveOneLineNamingThemAndTheOptions() throws Exception {
        InetAddress loopback = InetAddress.getLoopbackAddress();
        int p = FreePorts.range(RANGE);
        for (int port = p; port <= p + RANGE; port++) {
            hold(loopback, port);
        }
        DtronException e = assertThrows(DtronException.class, () -> Dtron.connect(options(loopback, p)).close());
        assertEquals("cannot join bus '" + cluster + "': no free port for the bus on 127.0.0.1 in " + p + ".."
                + (p + RANGE) + " (port " + p + ", port range " + RANGE + "): a member needs one, and ports " + p + "-"
                + (p + RANGE) + " are in use; choose free ones with the port and port range options (dtron: --port,"
                + " --port-range)", e.getMessage());
        assertNull(e.getCause(), "the message is the whole story");
    }

    @Test
    void aBindAddressOfAnotherHostIsNamedNotTakenForPortsInUse() throws Exception {
        InetAddress elsewhere = InetAddress.getByName("192.0.2.1"); // TEST-NET-1: never an address of this host
        DtronException e = assertThrows(DtronException.class, () -> Dtron.connect(options(elsewhere, 7800)).close());
        assertTrue(e.getMessage().startsWith("cannot join bus '" + cluster + "': cannot listen on 192.0.2.1, the bind"
                + " address: "), e.getMessage());
        assertTrue(e.getMessage().endsWith("; give an address of this host with the bind address option (dtron:"
                + " --bind)"), e.getMessage());
        assertFalse(e.getMessage().contains("in use"), e.getMessage());
    }

    @Test
    void aPortRangeOfZeroIsOneBusPort() throws Exception {
        int p = FreePorts.range(1);
        DtronOptions one = DtronOptions.builder().clusterName(cluster).port(p).portRange(0).build();
        try (Dtron a = Dtron.connect(one)) {
            DtronException e = assertThrows(DtronException.class, () -> Dtron.connect(one).close());
            assertTrue(e.getMessage().contains("ports " + p + " are in use"), e.getMessage());
        }
    }
}
