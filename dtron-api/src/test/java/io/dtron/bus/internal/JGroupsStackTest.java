package io.dtron.bus.internal;

import static org.junit.jupiter.api.Assertions.assertArrayEquals;
import static org.junit.jupiter.api.Assertions.assertEquals;
import static org.junit.jupiter.api.Assertions.assertInstanceOf;
import static org.junit.jupiter.api.Assertions.assertFalse;
import static org.junit.jupiter.api.Assertions.assertThrows;
import static org.junit.jupiter.api.Assertions.assertTrue;

import java.net.InetAddress;
import java.net.InetSocketAddress;
import java.util.Arrays;
import java.util.List;
import java.util.Optional;
import org.jgroups.protocols.FD_SOCK2;
import org.jgroups.protocols.TCP;
import org.jgroups.protocols.TP;
import org.jgroups.util.PassRegularMessagesUpDirectly;
import org.jgroups.protocols.TCPPING;
import org.jgroups.stack.Protocol;
import org.junit.jupiter.api.Test;

class JGroupsStackTest {
    private static final InetAddress LOOPBACK = InetAddress.getLoopbackAddress();

    private static JGroupsSettings settings(Optional<String> secret, boolean encrypt, boolean inJvm) {
        return new JGroupsSettings("c", "m", LOOPBACK, 7800, 61, List.of(), secret, encrypt, inJvm);
    }

    private static List<String> names(List<Protocol> stack) {
        return stack.stream().map(p -> p.getClass().getSimpleName()).toList();
    }

    @Test
    void defaultStackIsTcpOnLoopbackWithTotalOrder() {
        List<Protocol> stack = JGroupsStack.build(settings(Optional.empty(), false, false), 7805);
        assertEquals(List.of("TCP", "TCPPING", "MERGE3", "FD_SOCK2", "FD_ALL3", "VERIFY_SUSPECT2", "NAKACK2",
                "UNICAST3", "STABLE", "GMS", "MFC", "UFC", "SEQUENCER", "FRAG2"), names(stack));
        TCP tcp = (TCP) stack.get(0);
        assertEquals(LOOPBACK, tcp.getBindAddress());
        assertEquals(7805, tcp.getBindPort(), "the bus port the transport chose");
        assertEquals(0, tcp.getPortRange());
        assertEquals("no-bundler", tcp.getBundlerType(), "the sending thread writes each message");
        assertInstanceOf(PassRegularMessagesUpDirectly.class, tcp.getMessageProcessingPolicy(),
                "the reading thread passes messages up");
        TCPPING ping = (TCPPING) stack.get(1);
        assertEquals(31, ping.getInitialHosts().size(), "the lower half of the range, the bus ports, is probed");
        assertEquals(0, ping.getPortRange());
        List<InetSocketAddress> probed = settings(Optional.empty(), false, false).discoveryAddresses();
        assertEquals(new InetSocketAddress(LOOPBACK, 7800), probed.get(0));
        assertEquals(new InetSocketAddress(LOOPBACK, 7830), probed.get(30));
        FD_SOCK2 fd = (FD_SOCK2) stack.get(3);
        assertEquals(LOOPBACK, fd.getBindAddress(), "failure detection listens on the bind address, not on all");
        assertEquals(31, fd.getOffset(), "at the bus port + 31, in the upper half of the range");
        assertEquals(0, fd.getPortRange(), "on that one port, where the other members look for it");
    }

    @Test
    void aPortRangeOfZeroLeavesNoRoomForFailureDetectionOverTcp() {
        IllegalArgumentException e = assertThrows(IllegalArgumentException.class, () -> new JGroupsSettings("c", "m",
                LOOPBACK, 7800, 0, List.of(), Optional.empty(), false, false));
        assertTrue(e.getMessage().contains("failure detection"), e.getMessage());
        assertEquals(0, new JGroupsSettings("c", "m", LOOPBACK, 7800, 0, List.of(), Optional.empty(), false, true)
                .portRange(), "in-JVM members have no sockets");
        assertEquals(1, new JGroupsSettings("c", "m", LOOPBACK, 7800, 1, List.of(), Optional.empty(), false, false)
                .busPorts(), "one bus port, 7800, and 7801 for failure detection");
    }

    @Test
    void eachInitialMemberIsProbedOverTheRange() throws Exception {
        InetAddress other = InetAddress.getByName("127.0.0.2");
        JGroupsSettings lan = new JGroupsSettings("c", "m", LOOPBACK, 7800, 5,
                List.of(new InetSocketAddress(other, 9000), new InetSocketAddress(LOOPBACK, 7800)), Optional.empty(),
                false, false);
        assertEquals(List.of(new InetSocketAddress(other, 9000), new InetSocketAddress(other, 9001),
                new InetSocketAddress(other, 9002), new InetSocketAddress(LOOPBACK, 7800),
                new InetSocketAddress(LOOPBACK, 7801), new InetSocketAddress(LOOPBACK, 7802)),
                lan.discoveryAddresses());
    }

    @Test
    void authenticationSitsRightBelowMembershipAndEncryptionBelowReliability() {
        List<String> names = names(JGroupsStack.build(settings(Optional.of("s3cret"), true, false), 7800));
        assertEquals(names.indexOf("GMS") - 1, names.indexOf("AUTH"));
        assertEquals(names.indexOf("NAKACK2") - 1, names.indexOf("SYM_ENCRYPT"));
        List<String> authOnly = names(JGroupsStack.build(settings(Optional.of("s3cret"), false, false), 7800));
        assertTrue(authOnly.contains("AUTH"));
        assertFalse(authOnly.contains("SYM_ENCRYPT"));
    }

    @Test
    void inJvmStackHasNoSockets() {
        List<String> names = names(JGroupsStack.build(settings(Optional.empty(), false, true), 0));
        assertEquals(List.of("SHARED_LOOPBACK", "SHARED_LOOPBACK_PING"), names.subList(0, 2));
        TP loopback = (TP) JGroupsStack.build(settings(Optional.empty(), false, true), 0).get(0);
        assertEquals("no-bundler", loopback.getBundlerType(), "as over TCP: the sending thread delivers");
        assertInstanceOf(PassRegularMessagesUpDirectly.class, loopback.getMessageProcessingPolicy());
        assertFalse(names.contains("FD_SOCK2"));
        assertTrue(names.contains("SEQUENCER"));
    }

    @Test
    void encryptionNeedsASecret() {
        assertThrows(IllegalArgumentException.class, () -> settings(Optional.empty(), true, false));
    }

    @Test
    void keyDependsOnSecretAndCluster() {
        byte[] key = JGroupsStack.deriveKey("s3cret", "c").getEncoded();
        assertEquals(16, key.length);
        assertArrayEquals(key, JGroupsStack.deriveKey("s3cret", "c").getEncoded());
        assertFalse(Arrays.equals(key, JGroupsStack.deriveKey("s3cret!", "c").getEncoded()));
        assertFalse(Arrays.equals(key, JGroupsStack.deriveKey("s3cret", "d").getEncoded()));
    }

    @Test
    void settingsHideTheSecret() {
        assertFalse(settings(Optional.of("s3cret"), true, false).toString().contains("s3cret"));
    }
}
