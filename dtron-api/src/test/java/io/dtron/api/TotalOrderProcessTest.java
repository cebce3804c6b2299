package io.dtron.api;

import static org.junit.jupiter.api.Assertions.assertEquals;

import io.dtron.testadapter.OrderMemberMain;
import java.nio.file.Files;
import java.nio.file.Path;
import java.time.Duration;
import java.util.ArrayList;
import java.util.HashMap;
import java.util.List;
import java.util.Map;
import java.util.concurrent.TimeUnit;
import org.junit.jupiter.api.Test;
import org.junit.jupiter.api.Timeout;
import org.junit.jupiter.api.io.TempDir;

/**
 * Three JVMs publish 5,000 messages each at the same time over TCP on
 * loopback; every member must record all 15,000 in the same order.
 */
@Timeout(value = 180, unit = TimeUnit.SECONDS)
class TotalOrderProcessTest {
    private static final int MEMBERS = 3;
    private static final int MESSAGES = 5_000;

    @Test
    void everyMemberSeesAllMessagesOfAllSendersInOneOrder(@TempDir Path dir) throws Exception {
        String cluster = TestClusters.uniqueName("order");
        List<ChildJvm> children = new ArrayList<>();
        try {
            for (int i = 1; i <= MEMBERS; i++) {
                children.add(ChildJvm.start(OrderMemberMain.class, dir.resolve("m" + i + ".log"), cluster, "m" + i,
                        dir.resolve("m" + i + ".txt").toString(), String.valueOf(MESSAGES),
                        String.valueOf(MEMBERS)));
            }
            for (ChildJvm child : children) {
                assertEquals(0, child.waitFor(Duration.ofSeconds(150)), child.output());
            }
        } finally {
            children.forEach(ChildJvm::close);
        }

        List<String> reference = Files.readAllLines(dir.resolve("m1.txt"));
        assertEquals(MEMBERS * MESSAGES, reference.size());
        Map<String, Integer> lastBySender = new HashMap<>();
        for (String line : reference) {
            String[] fields = line.split(" ");
            int previous = lastBySender.getOrDefault(fields[0], 0);
            assertEquals(previous + 1, Integer.parseInt(fields[1]), "each sender's messages complete, in order");
            lastBySender.put(fields[0], previous + 1);
        }
        assertEquals(Map.of("m1", MESSAGES, "m2", MESSAGES, "m3", MESSAGES), lastBySender);
        for (int i = 2; i <= MEMBERS; i++) {
            assertEquals(reference, Files.readAllLines(dir.resolve("m" + i + ".txt")), "order at m" + i);
        }
    }
}
