package io.dtron.bus.internal;

import static org.junit.jupiter.api.Assertions.assertEquals;

import ch.qos.logback.classic.Level;
import io.dtron.testsupport.LogCapture;
import java.util.List;
import org.jgroups.logging.Slf4jLogImpl;
import org.junit.jupiter.api.Test;

/** JGroups' failure to send its graceful close on a socket closed at once is not an error; every other event is. */
class ClosingQuietLogTest {
    @Test
    void onlyTheFailedGracefulCloseIsNoError() {
        try (LogCapture log = new LogCapture(ClosingQuietLogTest.class)) {
            ClosingQuietLog quiet = new ClosingQuietLog(new Slf4jLogImpl(ClosingQuietLogTest.class));
            // as JGroups' TcpConnection logs it
            quiet.error("%s: failed sending graceful close to %s: %s", "127.0.0.1:7801", "127.0.0.1:7800",
                    "Socket closed");
            quiet.error("%s: exception setting send buffer to %d bytes: %s", "127.0.0.1:7801", 1024, "refused");
            quiet.warn("%s: failed handling message: %s", "127.0.0.1:7801", "Connection reset");
            assertEquals(List.of("127.0.0.1:7801: exception setting send buffer to 1024 bytes: refused"),
                    log.events(Level.ERROR).stream().map(e -> e.getFormattedMessage()).toList());
            assertEquals(List.of("127.0.0.1:7801: failed handling message: Connection reset"),
                    log.events(Level.WARN).stream().map(e -> e.getFormattedMessage()).toList());
        }
    }
}
