package io.dtron.api;

import static org.junit.jupiter.api.Assertions.assertNotNull;

import java.util.concurrent.BlockingQueue;
import java.util.concurrent.LinkedBlockingQueue;
import java.util.concurrent.TimeUnit;

/** A listener that keeps what it receives, for a test to take. */
class Inbox extends DtronListener {
    private final BlockingQueue<IDtronChannelValued> received = new LinkedBlockingQueue<>();

    Inbox(IDtronChannel channel) {
        super(channel);
    }

    @Override
    public void messageReceived(IDtronChannelValued message) {
        received.add(message);
    }

    /** Returns the next message, failing the test if none arrives within 10 seconds. */
    IDtronChannelValued take() throws InterruptedException {
        IDtronChannelValued message = received.poll(10, TimeUnit.SECONDS);
        assertNotNull(message, "no message on " + getChannel() + " within 10 s");
        return message;
    }

    /** Returns the next message if one arrives within a short while, else null. */
    IDtronChannelValued poll(long millis) throws InterruptedException {
        return received.poll(millis, TimeUnit.MILLISECONDS);
    }
}
