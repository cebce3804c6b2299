package io.dtron.selenium;

import static org.junit.jupiter.api.Assertions.assertEquals;
import static org.junit.jupiter.api.Assertions.assertNull;

import io.dtron.api.Dtron;
import io.dtron.api.DtronOptions;
import io.dtron.api.IDtronChannel;
import io.dtron.selenium.sample.Ping;
import io.dtron.testsupport.Inbox;
import java.util.Map;
import java.util.UUID;
import java.util.concurrent.TimeUnit;
import org.junit.jupiter.api.Test;
import org.junit.jupiter.api.Timeout;

/** A channel without a {@code user} variable is answered by a result without one; no browser is needed. */
@Timeout(value = 30, unit = TimeUnit.SECONDS)
class ResultWithoutUserTest {

    @Test
    void aChannelWithoutUserIsAnsweredByResCodeAlone() throws Exception {
        String cluster = "selenium-" + UUID.randomUUID().toString().substring(0, 8);
        Inbox results = new Inbox(IDtronChannel.of("result", "resCode"));
        SeleniumAdapters adapters = SeleniumAdapters.builder().adapter(Ping.class).driverFactory(() -> {
            throw new AssertionError("Ping needs no browser");
        }).build();
        try (Dtron tester = Dtron.connect(DtronOptions.builder().clusterName(cluster).inJvm(true).build());
                Dtron member = Dtron.connect(DtronOptions.builder().clusterName(cluster).inJvm(true).build())) {
            tester.addDtronListener(results);
            adapters.start(member);
            tester.send(IDtronChannel.of("ping").constructValued(Map.of()));
            assertEquals(Map.of("resCode", 0), results.take().getVariables());
            assertNull(results.poll(300));
        } finally {
            adapters.close();
        }
    }
}
