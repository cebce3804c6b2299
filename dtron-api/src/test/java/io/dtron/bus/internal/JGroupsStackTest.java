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
        assertEquals(List.of("GuardedTcp", "TCPPING", "MERGE3", "FD_ALL3", "VERIFY_SUSPECT2", "NAKACK2",
                "UNICAST3", "STABLE", "GMS", "MFC", "UFC", "SEQUENCER", "FRAG2"), names(stack));
        TCP tcp = (TCP) stack.get(0);
        assertTrue(tcp.enableSuspectEvents(), "a member whose connection breaks is suspected at once");
        assertEquals(LOOPBACK, tcp.getBindAddress());
        assertEquals(7805, tcp.getBindPort(), "the bus port the transport chose");
        assertEquals(0, tcp.getPortRange());
        assertEquals("no-bundler", tcp.getBundlerType(), "the sending thread writes each message");
        assertInstanceOf(PassRegularMessagesUpDirectly.class, tcp.getMessageProcessingPolicy(),
                "the reading thread passes messages up");
        TCPPING ping = (TCPPING) stack.get(1);
        assertEquals(62, ping.getInitialHosts().size(), "the whole range, the bus ports, is probed");
        assertEquals(0, ping.getPortRange());
        List<InetSocketAddress> probed = settings(Optional.empty(), false, false).discoveryAddresses();
        assertEquals(new InetSocketAddress(LOOPBACK, 7800), probed.get(0));
        assertEquals(new InetSocketAddress(LOOPBACK, 7861), probed.get(61));
    }

    @Test
    void aPortRangeOfZeroIsOneBusPort() {
        assertEquals(1, new JGroupsSettings("c", "m", LOOPBACK, 7800, 0, List.of(), Optional.empty(), false, false)
                .busPorts());
    }

    @Test
    void eachInitialMemberIsProbedOverTheRange() throws Exception {
        InetAddress other = InetAddress.getByName("127.0.0.2");
        JGroupsSettings lan = new JGroupsSettings("c", "m", LOOPBACK, 7800, 2,
                List.of(new InetSocketAddress(other, 9000), new InetSocketAddress(LOOPBACK, 7800)), Optional.empty(),
                false, false);
        assertEquals(List.of(new InetSocketAddress(other, 9000), new InetSocketAddress(other, 9001),
                new InetSocketAddress(other, 9002), new InetSocketAddress(LOOPBACK, 7800),
                new InetSocketAddress(LOOPBACK, 7801), new InetSocketAddress(LOOPBACK, 7802)),
                lan.discoveryAddresses());
    }

    @Test
    void encryptionSitsBelowReliabilityAndNoStackHasAuth() {
        List<String> names = names(JGroupsStack.build(settings(Optional.of("s3cret"), true, false), 7800));
        assertEquals(names.indexOf("NAKACK2") - 1, names.indexOf("SYM_ENCRYPT"));
        assertFalse(names.contains("AUTH"), "the codes of GuardedTcp keep out joins without the secret");
        List<String> codesOnly = names(JGroupsStack.build(settings(Optional.of("s3cret"), false, false), 7800));
        assertFalse(codesOnly.contains("SYM_ENCRYPT"));
    }

    @Test
    void inJvmStackHasNoSockets() {
        List<String> names = names(JGroupsStack.build(settings(Optional.empty(), false, true), 0));
        assertEquals(List.of("SHARED_LOOPBACK", "SHARED_LOOPBACK_PING"), names.subList(0, 2));
        TP loopback = (TP) JGroupsStack.build(settings(Optional.empty(), false, true), 0).get(0);
        assertEquals("no-bundler", loopback.getBundlerType(), "as over TCP: the sending thread delivers");
        assertInstanceOf(PassRegularMessagesUpDirectly.class, loopback.getMessageProcessingPolicy());
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
