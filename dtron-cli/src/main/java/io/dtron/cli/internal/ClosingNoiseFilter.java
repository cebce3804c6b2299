package io.dtron.cli.internal;

import ch.qos.logback.classic.spi.ILoggingEvent;
import ch.qos.logback.classic.spi.IThrowableProxy;
import ch.qos.logback.core.filter.Filter;
import ch.qos.logback.core.spi.FilterReply;
import java.util.Set;

/**
 * Not API. Drops the two events JGroups' TCP transport logs when a member leaves the bus while a connection of its
 * is busy, both about the member's own closing: "failed sending graceful close ... Socket closed" when two members
 * on one host close at the same time, and "failed handling message" (or, logged as JGRP000030 when a member leaves
 * right after it joined, "failed handling incoming message") with an {@code IOException: Stream closed} and its
 * stack trace, when the thread that read the member's last message (with direct message processing, the
 * thread that delivers it) reads again from the connection the member has just closed. The member is leaving
 * anyway, and the run's results are printed by then. No close order avoids the second: it comes from whichever
 * member leaves while another is still on the bus. Every other event passes, including other failures of the same
 * message. JGroups logs its transport's events under the transport's class: DTRON's {@code GuardedTcp}, or TCP.
 * Referenced from {@code logback.xml}.
 */
public final class ClosingNoiseFilter extends Filter<ILoggingEvent> {
    private static final Set<String> TCP_LOGGERS = Set.of("io.dtron.bus.internal.GuardedTcp",
            "org.jgroups.protocols.TCP");

    @Override
    public FilterReply decide(ILoggingEvent event) {
        String message = event.getFormattedMessage();
        if (!TCP_LOGGERS.contains(event.getLoggerName()) || message == null) {
            return FilterReply.NEUTRAL;
        }
        if (message.contains("failed sending graceful close")) {
            return FilterReply.DENY;
        }
        IThrowableProxy thrown = event.getThrowableProxy();
        if ((message.endsWith(": failed handling message") || message.endsWith(": failed handling incoming message"))
                && thrown != null
                && "java.io.IOException".equals(thrown.getClassName()) && "Stream closed".equals(thrown.getMessage())) {
            return FilterReply.DENY;
        }
        return FilterReply.NEUTRAL;
    }
}
