package io.dtron.testsupport;

import java.io.IOException;
import java.io.UncheckedIOException;
import java.net.InetAddress;
import java.net.UnknownHostException;
import java.nio.file.DirectoryStream;
import java.nio.file.Files;
import java.nio.file.Path;
import java.time.Duration;
import java.util.ArrayList;
import java.util.HashSet;
import java.util.List;
import java.util.Map;
import java.util.Set;
import java.util.concurrent.ConcurrentHashMap;
import org.awaitility.Awaitility;

/**
 * The listening sockets of a process, as {@code ss -ltnup} lists them, read from Linux's {@code /proc}: the TCP
 * sockets in state LISTEN and the unconnected UDP sockets whose inodes the process holds open.
 */
public final class ListeningSockets {
    private static final String TCP_LISTEN = "0A";
    private static final String UDP_UNCONNECTED = "07";

    private ListeningSockets() {
    }

    /** One listening socket: {@code tcp} or {@code udp}, its address (IPv4-mapped IPv6 addresses as IPv4) and port. */
    public record Listener(String protocol, InetAddress address, int port) {
        @Override
        public String toString() {
            return protocol + " " + address.getHostAddress() + ":" + port;
        }
    }

    /**
     * Returns, for each process (by pid), every listening socket it opened while it ran: their sockets are read
     * again and again (with Awaitility, every 50 ms) until all of them have exited, or {@code atMost} passed.
     */
    public static Map<Long, Set<Listener>> whileRunning(Duration atMost, ProcessHandle... processes) {
        Map<Long, Set<Listener>> seen = new ConcurrentHashMap<>();
        for (ProcessHandle process : processes) {
            seen.put(process.pid(), ConcurrentHashMap.newKeySet());
        }
        Awaitility.await().pollDelay(Duration.ZERO).pollInterval(Duration.ofMillis(50)).atMost(atMost).until(() -> {
            boolean running = false;
            for (ProcessHandle process : processes) {
                if (process.isAlive()) {
                    running = true;
                    try {
                        seen.get(process.pid()).addAll(of(process.pid()));
                    } catch (UncheckedIOException e) {
                        // it exited while its sockets were read
                    }
                }
            }
            return !running;
        });
        return seen;
    }

    /** Whether this system has {@code /proc/PID/net} to read. */
    public static boolean available() {
        return Files.isReadable(Path.of("/proc/self/net/tcp"));
    }

    /** Returns the listening sockets of the process, TCP and UDP, IPv4 and IPv6. */
    public static List<Listener> of(long pid) {
        try {
            Set<String> inodes = socketInodes(pid);
            List<Listener> listeners = new ArrayList<>();
            Path net = Path.of("/proc", Long.toString(pid), "net");
            for (String table : List.of("tcp", "tcp6", "udp", "udp6")) {
                String state = table.startsWith("tcp") ? TCP_LISTEN : UDP_UNCONNECTED;
                List<String> lines = Files.readAllLines(net.resolve(table));
                for (String line : lines.subList(1, lines.size())) {
                    String[] f = line.trim().split("\\s+");
                    if (f[3].equals(state) && inodes.contains(f[9])) {
                        String[] local = f[1].split(":");
                        listeners.add(new Listener(table.substring(0, 3), address(local[0]),
                                Integer.parseInt(local[1], 16)));
                    }
                }
            }
            return listeners;
        } catch (IOException e) {
            throw new UncheckedIOException(e);
        }
    }

    private static Set<String> socketInodes(long pid) throws IOException {
        Set<String> inodes = new HashSet<>();
        try (DirectoryStream<Path> fds = Files.newDirectoryStream(Path.of("/proc", Long.toString(pid), "fd"))) {
            for (Path fd : fds) {
                try {
                    String target = Files.readSymbolicLink(fd).toString();
                    if (target.startsWith("socket:[")) {
                        inodes.add(target.substring("socket:[".length(), target.length() - 1));
                    }
                } catch (IOException e) {
                    // the descriptor was closed meanwhile
                }
            }
        }
        return inodes;
    }

    /** The kernel's hex address: 32-bit words in host (little-endian) byte order. */
    private static InetAddress address(String hex) throws UnknownHostException {
        byte[] bytes = new byte[hex.length() / 2];
        for (int word = 0; word < bytes.length / 4; word++) {
            for (int i = 0; i < 4; i++) {
                int at = word * 8 + (3 - i) * 2;
                bytes[word * 4 + i] = (byte) Integer.parseInt(hex.substring(at, at + 2), 16);
            }
        }
        return InetAddress.getByAddress(bytes); // an IPv4-mapped IPv6 address comes back as IPv4
    }
}
