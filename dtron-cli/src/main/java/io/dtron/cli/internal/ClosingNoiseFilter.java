package io.dtron.cli.internal;

import ch.qos.logback.classic.spi.ILoggingEvent;
import ch.qos.logback.core.filter.Filter;
import ch.qos.logback.core.spi.FilterReply;

/**
 * Not API. Drops the one error JGroups' TCP transport logs when two members on one host close at the same time
 * ("failed sending graceful close ... Socket closed"): the members are leaving anyway, and the run's results are
 * printed by then. Every other event passes. Referenced from {@code logback.xml}.
 */
public final class ClosingNoiseFilter extends Filter<ILoggingEvent> {
    private static final String TCP_LOGGER = "org.jgroups.protocols.TCP";

    @Override
    public FilterReply decide(ILoggingEvent event) {
        if (TCP_LOGGER.equals(event.getLoggerName()) && event.getFormattedMessage() != null
                && event.getFormattedMessage().contains("failed sending graceful close")) {
            return FilterReply.DENY;
        }
        return FilterReply.NEUTRAL;
    }
}
