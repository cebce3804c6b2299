package io.dtron.bus.internal;

import org.jgroups.logging.Log;

/**
 * Not API. The log of {@link GuardedTcp}'s connections: JGroups' log of the transport, with one event of a member's
 * own leaving at debug level instead of error. When both ends close a connection at once (a member leaving while
 * its peer closes the connection, or its own reader closing it on the peer's close), JGroups fails to write its
 * graceful close on the socket the other closed and logs "failed sending graceful close ... Socket closed" (or
 * "Broken pipe"): the connection ends as it was to. Everything else passes as it is.
 */
final class ClosingQuietLog implements Log {
    private static final String GRACEFUL_CLOSE = "failed sending graceful close";

    private final Log log;

    ClosingQuietLog(Log log) {
        this.log = log;
    }

    @Override
    public void error(String format, Object... args) {
        if (format != null && format.contains(GRACEFUL_CLOSE)) {
            log.debug(format, args);
        } else {
            log.error(format, args);
        }
    }

    @Override
    public boolean isFatalEnabled() {
        return log.isFatalEnabled();
    }

    @Override
    public boolean isErrorEnabled() {
        return log.isErrorEnabled();
    }

    @Override
    public boolean isWarnEnabled() {
        return log.isWarnEnabled();
    }

    @Override
    public boolean isInfoEnabled() {
        return log.isInfoEnabled();
    }

    @Override
    public boolean isDebugEnabled() {
        return log.isDebugEnabled();
    }

    @Override
    public boolean isTraceEnabled() {
        return log.isTraceEnabled();
    }

    @Override
    public void fatal(String msg) {
        log.fatal(msg);
    }

    @Override
    public void fatal(String format, Object... args) {
        log.fatal(format, args);
    }

    @Override
    public void fatal(String msg, Throwable throwable) {
        log.fatal(msg, throwable);
    }

    @Override
    public void error(String msg) {
        log.error(msg);
    }

    @Override
    public void error(String msg, Throwable throwable) {
        log.error(msg, throwable);
    }

    @Override
    public void warn(String msg) {
        log.warn(msg);
    }

    @Override
    public void warn(String format, Object... args) {
        log.warn(format, args);
    }

    @Override
    public void warn(String msg, Throwable throwable) {
        log.warn(msg, throwable);
    }

    @Override
    public void info(String msg) {
        log.info(msg);
    }

    @Override
    public void info(String format, Object... args) {
        log.info(format, args);
    }

    @Override
    public void debug(String msg) {
        log.debug(msg);
    }

    @Override
    public void debug(String format, Object... args) {
        log.debug(format, args);
    }

    @Override
    public void debug(String msg, Throwable throwable) {
        log.debug(msg, throwable);
    }

    @Override
    public void trace(Object obj) {
        log.trace(obj);
    }

    @Override
    public void trace(String msg) {
        log.trace(msg);
    }

    @Override
    public void trace(String format, Object... args) {
        log.trace(format, args);
    }

    @Override
    public void trace(String msg, Throwable throwable) {
        log.trace(msg, throwable);
    }

    @Override
    public void setLevel(String level) {
        log.setLevel(level);
    }

    @Override
    public String getLevel() {
        return log.getLevel();
    }
}
