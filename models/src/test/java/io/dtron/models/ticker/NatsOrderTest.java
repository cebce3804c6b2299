package io.dtron.models.ticker;

import io.dtron.testsupport.NatsServer;
import java.nio.file.Path;
import java.time.Duration;
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
        try (NatsServer server = NatsServer.start(dir);
                OrderMembers members = new OrderMembers(dir, NatsTickerTest.cluster("order"), MESSAGES, server.url(),
                        server.url(), server.url())) {
            members.awaitSuccess(Duration.ofSeconds(150), Duration.ofSeconds(30));
            members.assertOneOrder();
        }
    }
}
