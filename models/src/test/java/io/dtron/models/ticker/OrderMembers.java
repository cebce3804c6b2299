package io.dtron.models.ticker;

import static org.junit.jupiter.api.Assertions.assertEquals;
import static org.junit.jupiter.api.Assertions.assertTrue;

import io.dtron.api.ChildJvm;
import io.dtron.testadapter.OrderMemberMain;
import java.io.IOException;
import java.nio.file.Files;
import java.nio.file.Path;
import java.time.Duration;
import java.util.HashSet;
import java.util.List;
import java.util.concurrent.TimeUnit;

/**
 * A Java, a Python and a C member of one NATS bus, each in a process of its own, each publishing {@code messages}
 * messages and recording every message it receives, in order, into {@code java.txt}, {@code python.txt} and
 * {@code c.txt} in a folder, with their logs beside.
 */
final class OrderMembers implements AutoCloseable {
    private final Path dir;
    private final int messages;
    private final ChildJvm java;
    private final Process python;
    private final Process c;

    /** Starts the three members, on the servers of {@code urls} (Java, Python and C in that order). */
    OrderMembers(Path dir, String bus, int messages, String javaUrl, String pythonUrl, String cUrl)
            throws Exception {
        this.dir = dir;
        this.messages = messages;
        String pythonBinary = NatsClients.python();
        Path cProgram = NatsClients.cProgram("dtron-order-member");
        String count = Integer.toString(messages);
        java = ChildJvm.start(OrderMemberMain.class, dir.resolve("java.log"), bus, "java",
                dir.resolve("java.txt").toString(), count, "3", javaUrl);
        Process started = null;
        try {
            started = new ProcessBuilder(pythonBinary, NatsClients.PYTHON.resolve("tests/order_member.py").toString(),
                    pythonUrl, bus, "python", dir.resolve("python.txt").toString(), count, "3")
                    .redirectErrorStream(true).redirectOutput(dir.resolve("python.log").toFile()).start();
            c = new ProcessBuilder(cProgram.toString(), cUrl, bus, "c", dir.resolve("c.txt").toString(), count, "3")
                    .redirectErrorStream(true).redirectOutput(dir.resolve("c.log").toFile()).start();
        } catch (IOException | RuntimeException e) {
            if (started != null) {
                started.destroyForcibly();
            }
            java.close();
            throw e;
        }
        python = started;
    }

    /** Waits for the three members to end, each successfully: the Python one first, as the slowest. */
    void awaitSuccess(Duration python, Duration others) throws Exception {
        assertTrue(this.python.waitFor(python.toMillis(), TimeUnit.MILLISECONDS), "python still running");
        assertTrue(c.waitFor(others.toMillis(), TimeUnit.MILLISECONDS), "c still running");
        assertEquals(0, this.python.exitValue(), Files.readString(dir.resolve("python.log")));
        assertEquals(0, c.exitValue(), Files.readString(dir.resolve("c.log")));
        assertEquals(0, java.waitFor(others), java.output());
    }

    /**
     * Asserts that every member recorded every message of every member once, each member's {@code messages}, and
     * all in the same order; returns that order.
     */
    List<String> assertOneOrder() throws IOException {
        List<String> javaOrder = Files.readAllLines(dir.resolve("java.txt"));
        assertEquals(3 * messages, javaOrder.size(), "every message once");
        assertEquals(3 * messages, new HashSet<>(javaOrder).size(), "no message twice");
        for (String sender : List.of("java", "python", "c")) {
            assertEquals(messages, javaOrder.stream().filter(l -> l.startsWith(sender + " ")).count(), sender);
        }
        assertEquals(javaOrder, Files.readAllLines(dir.resolve("python.txt")), "Python's order is Java's");
        assertEquals(javaOrder, Files.readAllLines(dir.resolve("c.txt")), "C's order is Java's");
        return javaOrder;
    }

    @Override
    public void close() {
        python.destroyForcibly();
        c.destroyForcibly();
        java.close();
    }
}
