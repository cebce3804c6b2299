package io.dtron.bridge.internal;

import io.dtron.api.IDtronChannelValued;
import io.dtron.bridge.LatencySummary;
import java.util.Arrays;

/**
 * Not API. Records t2 - t1 (receive time minus publish time) of received messages, in microseconds.
 * Messages without a publish time (senders of the original protocol) are left out. Thread-safe.
 */
public final class LatencyRecorder {
    private long[] micros = new long[1024];
    private int size;

    /** Records one received message. */
    public synchronized void record(IDtronChannelValued message) {
        if (message.getPublishTimeNanos() == 0) {
            return;
        }
        if (size == micros.length) {
            micros = Arrays.copyOf(micros, size * 2);
        }
        micros[size++] = Math.floorDiv(message.getReceiveTimeNanos() - message.getPublishTimeNanos(), 1000);
    }

    /** Returns the summary of the messages recorded so far. */
    public synchronized LatencySummary summary() {
        return LatencySummary.of(Arrays.copyOf(micros, size));
    }
}
