package io.dtron.cli.internal;

import static org.junit.jupiter.api.Assertions.assertEquals;

import ch.qos.logback.classic.Level;
import ch.qos.logback.classic.Logger;
import ch.qos.logback.classic.LoggerContext;
import ch.qos.logback.classic.spi.LoggingEvent;
import ch.qos.logback.core.spi.FilterReply;
import org.junit.jupiter.api.Test;

class ClosingNoiseFilterTest {
    private final LoggerContext context = new LoggerContext();
    private final ClosingNoiseFilter filter = new ClosingNoiseFilter();

    private FilterReply decide(String logger, String message) {
        Logger l = context.getLogger(logger);
        return filter.decide(new LoggingEvent(Logger.class.getName(), l, Level.ERROR, message, null, null));
    }

    @Test
    void dropsOnlyTheGracefulCloseErrorOfJGroupsTcp() {
        assertEquals(FilterReply.DENY, decide("org.jgroups.protocols.TCP",
                "127.0.0.1:7801: failed sending graceful close to 127.0.0.1:7800: Socket closed"));
        assertEquals(FilterReply.NEUTRAL, decide("org.jgroups.protocols.TCP", "127.0.0.1:7801: failed connecting"));
        assertEquals(FilterReply.NEUTRAL, decide("io.dtron.api.Dtron", "failed sending graceful close"));
    }
}
