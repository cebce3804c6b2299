package io.dtron.testsupport;

import io.dtron.api.DtronOptions;
import java.io.IOException;
import java.io.UncheckedIOException;
import java.net.InetAddress;
import java.net.ServerSocket;
import java.util.concurrent.ThreadLocalRandom;

/**
 * Free ports for tests, so that no test depends on a fixed port (7800, the bus's default) being free: other tests,
 * other builds and other buses may hold them.
 */
public final class FreePorts {
    /** Below Linux's ephemeral ports (32768 and up), which outgoing connections take. */
    private static final int LOWEST = 10_000;
    private static final int HIGHEST = 32_000;

    /** The port range of a test's bus: 8 bus ports. */
    public static final int BUS_RANGE = 7;

    private FreePorts() {
    }

    /**
     * Sets the bus's first port (with the range {@link #BUS_RANGE}) from a test main's argument {@code args[at]}, if
     * it was given: the port the test picked for its bus with {@link #range}.
     */
    public static DtronOptions.Builder onPort(DtronOptions.Builder options, String[] args, int at) {
        return args.length > at ? options.port(Integer.parseInt(args[at])).portRange(BUS_RANGE) : options;
    }

    /** Returns a port that is free now at every address (127.0.0.1 when none is given). */
    public static int port(InetAddress... addresses) {
        return range(0, addresses);
    }

    /**
     * Returns the first port P of a range {@code P .. P+range} whose ports are all free now at every address
     * (127.0.0.1 when none is given): the {@code --port} of a bus with {@code --port-range range}. It starts at a
     * random port, so that tests running at once seldom pick the same range.
     */
    public static int range(int range, InetAddress... addresses) {
        InetAddress[] at = addresses.length == 0 ? new InetAddress[] {InetAddress.getLoopbackAddress()} : addresses;
        int span = HIGHEST - LOWEST - range;
        int start = ThreadLocalRandom.current().nextInt(span);
        for (int i = 0; i < span; i++) {
            int first = LOWEST + (start + i) % span;
            if (allFree(first, range, at)) {
                return first;
            }
        }
        throw new UncheckedIOException(new IOException("no " + (range + 1) + " free ports in a row below " + HIGHEST));
    }

    private static boolean allFree(int first, int range, InetAddress[] addresses) {
        for (int port = first; port <= first + range; port++) {
            for (InetAddress address : addresses) {
                try (ServerSocket probe = new ServerSocket(port, 1, address)) {
                    probe.setReuseAddress(true);
                } catch (IOException e) {
                    return false;
                }
            }
        }
        return true;
    }
}
