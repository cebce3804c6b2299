package io.dtron.cli.internal;

import static org.junit.jupiter.api.Assertions.assertEquals;

import ch.qos.logback.classic.Level;
import ch.qos.logback.classic.Logger;
import ch.qos.logback.classic.LoggerContext;
import ch.qos.logback.classic.spi.LoggingEvent;
import ch.qos.logback.core.spi.FilterReply;
import java.io.IOException;
import org.junit.jupiter.api.Test;

class ClosingNoiseFilterTest {
    private final LoggerContext context = new LoggerContext();
    private final ClosingNoiseFilter filter = new ClosingNoiseFilter();

    private FilterReply decide(String logger, String message) {
        return decide(logger, Level.ERROR, message, null);
    }

    private FilterReply decide(String logger, Level level, String message, Throwable thrown) {
        Logger l = context.getLogger(logger);
        return filter.decide(new LoggingEvent(Logger.class.getName(), l, level, message, thrown, null));
    }

    @Test
    void dropsOnlyTheGracefulCloseErrorOfJGroupsTcp() {
        assertEquals(FilterReply.DENY, decide("org.jgroups.protocols.TCP",
                "127.0.0.1:7801: failed sending graceful close to 127.0.0.1:7800: Socket closed"));
        assertEquals(FilterReply.NEUTRAL, decide("org.jgroups.protocols.TCP", "127.0.0.1:7801: failed connecting"));
        assertEquals(FilterReply.NEUTRAL, decide("io.dtron.api.Dtron", "failed sending graceful close"));
        assertEquals(FilterReply.DENY, decide("io.dtron.bus.internal.GuardedTcp",
                "127.0.0.1:7801: failed sending graceful close to 127.0.0.1:7800: Socket closed"),
                "DTRON's transport is JGroups' TCP, logging under its own name");
    }

    /** What JGroups 5.5 logs, with a stack trace, when a leaving member reads from the connection it closed. */
    @Test
    void dropsOnlyTheStreamClosedFailureOfAMemberReadingItsOwnClosedConnection() {
        String message = "127.0.0.1:7802: failed handling message";
        assertEquals(FilterReply.DENY, decide("org.jgroups.protocols.TCP", Level.WARN, message,
                new IOException("Stream closed")));
        assertEquals(FilterReply.NEUTRAL, decide("org.jgroups.protocols.TCP", Level.WARN, message,
                new IOException("Connection reset")), "another failure of a connection is news");
        assertEquals(FilterReply.NEUTRAL, decide("org.jgroups.protocols.TCP", Level.WARN, message,
                new IllegalStateException("Stream closed")), "so is another exception");
        assertEquals(FilterReply.NEUTRAL, decide("org.jgroups.protocols.TCP", Level.WARN, message, null));
        assertEquals(FilterReply.NEUTRAL, decide("io.dtron.api.Dtron", Level.WARN, message,
                new IOException("Stream closed")));
    }

    /** The same, as JGroups 5.5 logs it (JGRP000030) for a tester that was refused and left right after joining. */
    @Test
    void dropsTheStreamClosedFailureOfAnIncomingMessageToo() {
        String message = "JGRP000030: dtron-12546-2e4dd23d: failed handling incoming message";
        assertEquals(FilterReply.DENY, decide("org.jgroups.protocols.TCP", Level.ERROR, message,
                new IOException("Stream closed")));
        assertEquals(FilterReply.NEUTRAL, decide("org.jgroups.protocols.TCP", Level.ERROR, message,
                new IOException("Connection reset")), "another failure of a connection is news");
    }
}
