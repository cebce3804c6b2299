package io.dtron.models.ticker;

import static org.junit.jupiter.api.Assertions.assertEquals;
import static org.junit.jupiter.api.Assertions.assertTrue;

import io.dtron.api.ChildJvm;
import io.dtron.testadapter.OrderMemberMain;
import io.dtron.testsupport.NatsServer;
import java.nio.file.Files;
import java.nio.file.Path;
import java.time.Duration;
import java.util.HashSet;
import java.util.List;
import java.util.concurrent.TimeUnit;
import org.junit.jupiter.api.Test;
import org.junit.jupiter.api.Timeout;
import org.junit.jupiter.api.io.TempDir;

/**
 * One order across languages: a Java, a Python and a C member each publish 5,000 messages at once on one NATS bus,
 * and all three record every message, once, in the same order.
 */
@Timeout(value = 3, unit = TimeUnit.MINUTES)
class NatsOrderTest {
    private static final int MESSAGES = 5_000;

    @TempDir
    Path dir;

    @Test
    void javaPythonAndCMembersRecordTheSameOrder() throws Exception {
        String python = NatsClients.python();
        Path c = NatsClients.cProgram("dtron-order-member");
        try (NatsServer server = NatsServer.start(dir)) {
            String bus = NatsTickerTest.cluster("order");
            String count = Integer.toString(MESSAGES);
            try (ChildJvm java = ChildJvm.start(OrderMemberMain.class, dir.resolve("java.log"), bus, "java",
                    dir.resolve("java.txt").toString(), count, "3", server.url())) {
                Process py = new ProcessBuilder(python, NatsClients.PYTHON.resolve("tests/order_member.py").toString(),
                        server.url(), bus, "python", dir.resolve("python.txt").toString(), count, "3")
                        .redirectErrorStream(true).redirectOutput(dir.resolve("python.log").toFile()).start();
                Process cMember = new ProcessBuilder(c.toString(), server.url(), bus, "c",
                        dir.resolve("c.txt").toString(), count, "3")
                        .redirectErrorStream(true).redirectOutput(dir.resolve("c.log").toFile()).start();
                try {
                    assertTrue(py.waitFor(150, TimeUnit.SECONDS), "python still running");
                    assertTrue(cMember.waitFor(30, TimeUnit.SECONDS), "c still running");
                    assertEquals(0, py.exitValue(), Files.readString(dir.resolve("python.log")));
                    assertEquals(0, cMember.exitValue(), Files.readString(dir.resolve("c.log")));
                    assertEquals(0, java.waitFor(Duration.ofSeconds(30)), java.output());
                } finally {
                    py.destroyForcibly();
                    cMember.destroyForcibly();
                }
            }
            List<String> javaOrder = Files.readAllLines(dir.resolve("java.txt"));
            assertEquals(3 * MESSAGES, javaOrder.size());
            assertEquals(3 * MESSAGES, new HashSet<>(javaOrder).size(), "no message twice");
            for (String sender : List.of("java", "python", "c")) {
                assertEquals(MESSAGES, javaOrder.stream().filter(l -> l.startsWith(sender + " ")).count(), sender);
            }
            assertEquals(javaOrder, Files.readAllLines(dir.resolve("python.txt")), "Python's order is Java's");
            assertEquals(javaOrder, Files.readAllLines(dir.resolve("c.txt")), "C's order is Java's");
        }
    }
}
