package io.dtron.testsupport;

import static org.junit.jupiter.api.Assertions.assertNotNull;

import io.dtron.api.DtronListener;
import io.dtron.api.IDtronChannel;
import io.dtron.api.IDtronChannelValued;
import java.util.concurrent.BlockingQueue;
import java.util.concurrent.LinkedBlockingQueue;
import java.util.concurrent.TimeUnit;

/** A listener that keeps what it receives, for a test to take. */
public final class Inbox extends DtronListener {
    private final BlockingQueue<IDtronChannelValued> received = new LinkedBlockingQueue<>();

    /** An inbox for the messages on {@code channel}. */
    public Inbox(IDtronChannel channel) {
        super(channel);
    }

    @Override
    public void messageReceived(IDtronChannelValued message) {
        received.add(message);
    }

    /** Returns the next message, failing the test if none arrives within 20 seconds. */
    public IDtronChannelValued take() throws InterruptedException {
        IDtronChannelValued message = received.poll(20, TimeUnit.SECONDS);
        assertNotNull(message, "no message on " + getChannel() + " within 20 s");
        return message;
    }

    /** Returns the next message if one arrives within {@code millis}, else null. */
    public IDtronChannelValued poll(long millis) throws InterruptedException {
        return received.poll(millis, TimeUnit.MILLISECONDS);
    }
}
